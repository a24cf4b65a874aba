// flaplag CLI — --shard parts and flaplag merge: a part's case read as a command line.
#include "shard.h"

#include <vector>

#include "case_file.h"
#include "commands.h"
#include "options.h"

namespace flaplag::cli {

namespace {

using Json = nlohmann::ordered_json;

// A part's case as this command line reads it.
Request request_of_case(const std::string& file, const Json& case_object) {
  const CaseArguments a = case_object_arguments(file, case_object);
  const CommandLine cl(a.args);
  Request r = cl.interpret();
  r.arguments = a.args;
  return r;
}

class CommandLineCases : public documents::PartCases {
 public:
  documents::PartCase read(const std::string& file, const Json& case_object) const override {
    const Request r = request_of_case(file, case_object);
    const Request block = shard_request(r);
    documents::PartCase c;
    c.command = command_name(r.command);
    c.json = r.json;
    c.index = static_cast<std::size_t>(r.shard_index);
    c.count = static_cast<std::size_t>(r.shard_count);
    c.block = shard_block(r);
    c.x = block.x_values;
    c.y = block.y_values;
    c.vary = block.vary_values;
    return c;
  }

  // The command run on no lines of the split axis, as one run of the whole job.
  Json skeleton(const std::string& file, const Json& case_object,
                const std::string& axis) const override {
    Request r = request_of_case(file, case_object);
    r.shard_index = r.shard_count = 0;
    r.output.clear();
    r.plot.clear();
    r.quiet = true;
    if (axis == "vary") r.vary_values.clear();
    if (axis == "x") r.x_values.clear();
    if (axis == "y") r.y_values.clear();
    std::string warning;
    return Json::parse(run_command(r, &warning, nullptr));
  }
};

}  // namespace

ShardBlock shard_block(const Request& r) {
  const std::vector<double>* values = &r.vary_values;
  const char* axis = "vary";
  if (r.command == Command::Map) {
    const bool columns = r.y_name == "mu";
    axis = columns ? "x" : "y";
    values = columns ? &r.x_values : &r.y_values;
  }
  if (r.shard_count > 0)
    return documents::block_of(axis, values->size(), static_cast<std::size_t>(r.shard_index),
                               static_cast<std::size_t>(r.shard_count));
  return documents::block_of(axis, values->size(), 1, 1);
}

Request shard_request(const Request& r) {
  if (r.shard_count == 0) return r;
  const ShardBlock b = shard_block(r);
  Request part = r;
  std::vector<double>& v = r.command == Command::Map
                               ? (std::string(b.axis) == "x" ? part.x_values : part.y_values)
                               : part.vary_values;
  v = std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(b.first),
                          v.begin() + static_cast<std::ptrdiff_t>(b.last));
  return part;
}

Json shard_json(const Request& r) {
  return documents::shard_json(shard_block(r), static_cast<std::size_t>(r.shard_index),
                               static_cast<std::size_t>(r.shard_count));
}

const documents::PartCases& command_line_cases() {
  static const CommandLineCases cases;
  return cases;
}

std::string merge_parts(const Request& r) {
  return documents::merge_parts(r.inputs, r.memory_limit, command_line_cases(), kebab_option);
}

}  // namespace flaplag::cli
