// flaplag CLI — reading the files flaplag is given (case files, results for plot, run and merge)
// with bounds: a file is read whole only up to a size limit, and its nesting is counted by a
// flat scan (no recursion) before a parser that recurses sees it.  Every file flaplag reads
// goes through here.
//
// The limits, and why:
// - kMaxNesting = 64 levels.  flaplag writes at most 5 (a study row's intervals), a case file
//   2 ([group] key = value).  toml++ and nlohmann recurse per level (in parsing, comparing,
//   printing or freeing), and a few ten thousand levels overflow the stack.
// - kMaxResultBytes = 64 MiB for a JSON file (a result given to plot, run or merge, or a JSON
//   case).  flaplag writes about 58 bytes per map cell, so this is a map of a million cells
//   (1000 x 1000), far beyond what a part or a picture needs.  Reading JSON takes about 2.2
//   times the file in memory for flaplag's results and at most about 20 times for any JSON
//   (the worst being "[0,0,0,...]"), so a file at the limit is read in at most ~1.3 GB.
// - kMaxCaseBytes = 4 MiB for a TOML case file.  A case is a few dozen keys; its longest value,
//   an explicit list of 100 000 values for --vary, is about 1 MB.  toml++ takes up to ~40
//   times the text in memory (short array items), ~160 MB at the limit.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace flaplag::cli {

inline constexpr std::size_t kMaxNesting = 64;
inline constexpr std::size_t kMaxResultBytes = std::size_t{64} << 20;
inline constexpr std::size_t kMaxCaseBytes = std::size_t{4} << 20;

// "64 MiB".
std::string size_text(std::size_t bytes);

// The whole file at `path` (as typed).  Throws InvalidInput("argument", shown(path), reason):
// `cannot_read` when it cannot be opened or read, "is a directory, not a <noun>", or "larger
// than <max_bytes> (the limit on a <noun>)".  Reads at most max_bytes + 1 bytes whatever the
// file is (a device, a FIFO, a file that grows).
std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& noun,
                           const std::string& cannot_read);

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

}  // namespace flaplag::cli
