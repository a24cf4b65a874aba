// flaplag documents — the parts of a map or study computed as a batch job (--shard I/N in the
// command line: one task of a scheduler's job array), and their merge into exactly the file one
// run writes.
//
// A map is computed in lines (study.h): rows, one per y value, or columns, one per x value,
// when y is mu (a continuation in mu is one line and is never split, so that every cell of a
// part is bit for bit the cell of the whole run).  A study's lines are its values.  Part I of N
// (1-based, as Slurm's SLURM_ARRAY_TASK_ID with --array=1-N) computes the contiguous block of
// lines [floor((I-1) L / N), floor(I L / N)) of L: blocks in order, sizes differing by at most
// one, empty when N > L.  A part is a valid result of its own block (the split axis holds the
// block's values) with a "shard" object saying which block it is, sealed by a digest.
//
// A part's "case" is the command line that computed it, in the vocabulary of the front end
// that wrote it: the merge asks that front end (PartCases) what the case computes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flaplag/documents/names.h"

namespace flaplag::documents {

struct ShardBlock {
  const char* axis = "";                       // "y" or "x" (map), "vary" (study)
  std::size_t first = 0, last = 0, total = 0;  // lines [first, last) of total
};

// Lines [first, last) of part `index` (1-based) of `count` over `total` lines.
ShardBlock block_of(const char* axis, std::size_t total, std::size_t index, std::size_t count);

// The "shard" object of a part's JSON: index, count, axis, first, last, total.
nlohmann::ordered_json shard_json(const ShardBlock& b, std::size_t index, std::size_t count);

// Adds the part's digest to its "shard" object ("digest": "sha256:" + 64 hex digits): the SHA-256
// (digest.h) of the compact dump of the document without the digest.  The last change made to a
// part's JSON before it is written.
void seal_part(nlohmann::ordered_json& j);

// What a part's case computes, as the front end whose command line it is reads it.
struct PartCase {
  std::string command;               // "map" or "study"
  bool json = false;                 // the case writes JSON
  std::size_t index = 0, count = 0;  // its part: index of count (0 of 0: not a part)
  ShardBlock block;                  // the lines of that part
  std::vector<double> x, y, vary;    // the part's values on each axis (map, study)
};

class PartCases {
 public:
  virtual ~PartCases() = default;
  // What `case_object` (of the part `file`, as typed) asks for.  Throws InvalidInput when it is
  // not a command the front end takes.
  virtual PartCase read(const std::string& file,
                        const nlohmann::ordered_json& case_object) const = 0;
  // The output of `case_object` without the lines of `axis` ("x", "y" or "vary"), as one run of
  // the whole job: what every part must hold besides its data (model, method, parameters, names,
  // the other axis of a map).  Throws InvalidInput as read().
  virtual nlohmann::ordered_json skeleton(const std::string& file,
                                          const nlohmann::ordered_json& case_object,
                                          const std::string& axis) const = 0;
};

// The parts `files` (as typed, in any order) as the JSON text one run of their case writes.  A
// part must prove it is what its case computes: its digest matches its data; its case is a
// command the front end takes (cases), of this part of the job; its "shard" block is the one its
// index is; its axis values are exactly the block's values of the case's grid (and the other
// axis all of it); everything but the data (model, method, parameters, names) is what the
// case's command writes; its arrays have the block's shape; every cell and row has the types
// flaplag writes, mode labels of the case's model, known kinds and statuses.  Throws
// InvalidInput("argument", the file as typed, reason) for a file that cannot be read, is not a
// part or an interrupted one, fails one of those checks, belongs to another case (other options,
// another count N, another flaplag) or repeats a part; InvalidInput("argument", "(missing)",
// reason) naming the parts that are missing; and check_merged_size's refusal.  The parts
// together are read within json_read_limit(memory_limit) bytes; `option` spells the fields
// named in refusals (memory_limit, json, shard).
std::string merge_parts(const std::vector<std::string>& files, std::uint64_t memory_limit,
                        const PartCases& cases, const Spelling& option);

// Before the merged text is made: throws InvalidInput("memory_limit", ...) when the JSON text of
// `merged` (dump(2), computed exactly without making it) and the documents behind it need more
// than memory_limit (limits.h json_output_memory), saying how large the parts `files` are: a
// part that grows a thousandfold when written out was not written by flaplag.
void check_merged_size(const std::vector<std::string>& files, std::uint64_t memory_limit,
                       const nlohmann::ordered_json& merged);

}  // namespace flaplag::documents
