// flaplag CLI — --shard I/N: one part of a map or study (merge.h: the parts and their merge), and
// `flaplag merge`.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "command_line.h"
#include "flaplag/documents/merge.h"

namespace flaplag::cli {

using documents::ShardBlock;

// The block of part r.shard_index of r.shard_count (the whole job when r.shard_count == 0).
ShardBlock shard_block(const Request& r);

// r with only the block's values on the split axis.
Request shard_request(const Request& r);

// The "shard" object of a part's JSON: index, count, axis, first, last, total.
nlohmann::ordered_json shard_json(const Request& r);

using documents::seal_part;

// A part's case read as this command line reads it (for documents::merge_parts).
const documents::PartCases& command_line_cases();

// `flaplag merge`: the parts r.inputs (in any order) as the JSON text the command writes without
// --shard (documents::merge_parts, each part's case read as this command line reads it).
std::string merge_parts(const Request& r);

}  // namespace flaplag::cli
