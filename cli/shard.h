// flaplag CLI — batch jobs: one part of a map or study (--shard I/N, one task of a scheduler's
// job array) and `flaplag merge`, which joins the parts into exactly the file one run writes.
//
// A map is computed in lines (study.h): rows, one per y value, or columns, one per x value,
// when y is mu (a continuation in mu is one line and is never split, so that every cell of a
// part is bit for bit the cell of the whole run).  A study's lines are its values.  Part I of N
// (1-based, as Slurm's SLURM_ARRAY_TASK_ID with --array=1-N) computes the contiguous block of
// lines [floor((I-1) L / N), floor(I L / N)) of L: blocks in order, sizes differing by at most
// one, empty when N > L.  A part is a valid result of its own block (the split axis holds the
// block's values) with a "shard" object saying which block it is.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "command_line.h"

namespace flaplag::cli {

struct ShardBlock {
  const char* axis = "";                       // "y" or "x" (map), "vary" (study)
  std::size_t first = 0, last = 0, total = 0;  // lines [first, last) of total
};

// The block of part r.shard_index of r.shard_count (the whole job when r.shard_count == 0).
ShardBlock shard_block(const Request& r);

// r with only the block's values on the split axis.
Request shard_request(const Request& r);

// The "shard" object of a part's JSON: index, count, axis, first, last, total.
nlohmann::ordered_json shard_json(const Request& r);

// Adds the part's digest to its "shard" object ("digest": "sha256:" + 64 hex digits): the SHA-256
// (digest.h) of the compact dump of the document without the digest.  The last change made to a
// part's JSON before it is written.
void seal_part(nlohmann::ordered_json& j);

// `flaplag merge`: the parts r.inputs (in any order) as the JSON text the command writes without
// --shard.  A part must prove it is what its case computes: its digest matches its data; its
// case is a command line flaplag takes, of this part of the job; its "shard" block is the one
// flaplag computes for that index; its axis values are exactly the block's values of the case's
// grid (and the other axis all of it); everything but the data (model, method, parameters, names)
// is what the case's command writes; its arrays have the block's shape; every cell and row has
// the types flaplag writes, mode labels of the case's model, known kinds and statuses.  Throws
// InvalidInput("argument", the file as typed, reason) for a file that cannot be read, is not a
// flaplag --shard part or an interrupted one, fails one of those checks, belongs to another
// case (other options, another count N, another flaplag) or repeats a part; and
// InvalidInput("argument", "(missing)", reason) naming the parts that are missing.
std::string merge_parts(const Request& r);

}  // namespace flaplag::cli
