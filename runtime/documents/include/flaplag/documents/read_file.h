// flaplag documents — reading the files flaplag is given (case files, results to plot, run, report
// and merge)
// with bounds: a file is read whole only up to a size limit, and its nesting is counted by a
// flat scan (no recursion) before a parser that recurses sees it.  Every file flaplag reads
// goes through here.
//
// The limits, and why:
// - kMaxNesting = 64 levels.  flaplag writes at most 5 (a study row's intervals), a case file
//   2 ([group] key = value).  toml++ and nlohmann recurse per level (in parsing, comparing,
//   printing or freeing), and a few ten thousand levels overflow the stack.
// - A JSON file (a result given to plot, run or merge, or a JSON case; merge: all its parts
//   together) is read up to json_read_limit(memory limit) = the memory limit / kJsonMemoryFactor
//   (128 MiB at the default 2 GiB): reading JSON takes about 2.2 times the file in memory for
//   flaplag's results and about 16 times at the worst (measured: "[0,0,0,...]" of 64 MiB
//   peaks at 1.05 GB), so a file takes about the memory limit (limits.h)
//   at the most.  flaplag writes about 58 bytes per map cell: 2.3 million cells at the
//   default; a larger result is read with the memory limit raised, as it was written.
// - kMaxCaseBytes = 4 MiB for a TOML case file.  A case is a few dozen keys; its longest value,
//   an explicit list of 100 000 values of a varied parameter, is about 1 MB.  toml++ takes up to
//   ~40 times the text in memory (short array items), ~160 MB at the limit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "flaplag/documents/names.h"

namespace flaplag::documents {

inline constexpr std::size_t kMaxNesting = 64;
inline constexpr std::uint64_t kJsonMemoryFactor = 16;
// The largest JSON file read under a memory limit (bytes): limit / kJsonMemoryFactor.
std::size_t json_read_limit(std::uint64_t memory_limit);
inline constexpr std::size_t kMaxCaseBytes = std::size_t{4} << 20;

// "64 MiB".
std::string size_text(std::size_t bytes);

// The whole file at `path` (as typed).  Throws InvalidInput("argument", shown(path), reason):
// `cannot_read` when it cannot be opened or read, "is a directory, not a <noun>", or "larger
// than <max_bytes> (the limit on a <noun><why>)".  Reads at most max_bytes + 1 bytes whatever the
// file is (a device, a FIFO, a file that grows).
std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& noun,
                           const std::string& cannot_read, const std::string& why = "");
// A JSON file under the memory limit: read_text_file with json_read_limit(memory_limit), the
// reason naming the limit and how to raise it (the field memory_limit as `option` spells it).
std::string read_json_file(const std::string& path, std::uint64_t memory_limit,
                           const std::string& noun, const std::string& cannot_read,
                           const Spelling& option);

// The line (1-based) at which the nesting of JSON text first exceeds `limit` levels of [ and {
// outside strings, or 0 when it never does.  One pass, constant stack.
std::size_t json_too_deep(std::string_view text, std::size_t limit = kMaxNesting);

// The same for TOML text, counting outside strings and comments: the [ and { open around a
// value, the dots of the dotted keys on the way to it ("a.b.c = 1" counts 2) and the depth of the
// current [table] header (its dots + 1).  Every level of toml++'s tables and arrays is one of
// these or the key just before one, so text that passes nests at most 2 * limit + 1 deep.  (The
// dot of a float counts too: one per number, harmless.)
std::size_t toml_too_deep(std::string_view text, std::size_t limit = kMaxNesting);

// Parses JSON text: the depth is checked first (json_too_deep), then nlohmann's parser (which
// holds its state on the heap), refusing a key given twice in one object (nlohmann would keep
// the last silently).  NotJson: a syntax error (*error: the parser's message); Refused: JSON
// that flaplag does not read (*error: "nested deeper than 64 levels (line 3)", "key \"theta\"
// given twice in one object (at case.theta)").
enum class JsonParse { Ok, NotJson, Refused };
JsonParse parse_json(const std::string& text, nlohmann::json* out, std::string* error);
JsonParse parse_json(const std::string& text, nlohmann::ordered_json* out, std::string* error);

}  // namespace flaplag::documents
