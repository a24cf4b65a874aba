// flaplag documents — SHA-256 (FIPS 180-4), for the digest a --shard part carries of its own data.
//
// A digest with no key: it detects a part that was damaged or edited after flaplag wrote it (a
// cell changed by hand, a file cut short or mangled in transfer), not a forger, who can compute
// it again after editing.  Against a forged part merge has its structural checks (shard.h).
#pragma once

#include <string>
#include <string_view>

namespace flaplag::documents {

// The SHA-256 of `data` as 64 lowercase hex digits.
std::string sha256_hex(std::string_view data);

}  // namespace flaplag::documents
