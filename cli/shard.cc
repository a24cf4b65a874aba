// flaplag CLI — --shard parts and flaplag merge.
#include "shard.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "flaplag/core/errors.h"
#include "options.h"

namespace flaplag::cli {

namespace {

using Json = nlohmann::ordered_json;

[[noreturn]] void refuse(const std::string& file, const std::string& reason) {
  throw InvalidInput("argument", shown(file), reason);
}

// The keys that hold the values of the split lines: they differ from part to part.
std::vector<std::string> data_keys(const std::string& command) {
  if (command == "study") return {"rows"};
  return {"max_zeta", "mode", "kind"};
}

// Far above any real job (a map has at most 10000 lines, a study 100000 values); a larger
// number in a file is damage, not a job.
constexpr std::size_t kMaxCount = 100000;

// Lines [first, last) of part `index` (1-based) of `count` over `total` lines.
void block_of(std::size_t total, std::size_t index, std::size_t count, ShardBlock& b) {
  b.total = total;
  b.first = total * (index - 1) / count;
  b.last = total * index / count;
}

int status_rank(const std::string& s) { return s == "ok" ? 0 : s == "warning" ? 1 : 2; }

struct Part {
  std::string file;  // as typed
  Json json;
  std::size_t index = 0, count = 0, first = 0, last = 0, total = 0;
  std::string axis;
};

Json read_json(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) refuse(file, "cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) refuse(file, "cannot be read");
  try {
    return Json::parse(ss.str());
  } catch (const Json::exception&) {
    refuse(file, "not JSON (a part is the --json output of flaplag map or study with --shard)");
  }
}

std::size_t count_of(const Json& shard, const char* key, const std::string& file) {
  const auto it = shard.find(key);
  if (it == shard.end() || !it->is_number_unsigned())
    refuse(file, std::string("damaged part: \"shard\" has no whole number \"") + key + "\"");
  return it->get<std::size_t>();
}

// The values on the split axis of a part, and its data arrays, checked against the block.
const Json& axis_values(const Part& p) {
  const Json& j = p.json;
  if (p.axis == "vary") return j.at("rows");
  return j.at(p.axis).at("values");
}

Part read_part(const std::string& file) {
  Part p;
  p.file = file;
  p.json = read_json(file);
  const Json& j = p.json;
  if (!j.is_object() || !j.contains("flaplag") || !j.contains("command") ||
      !j["command"].is_string())
    refuse(file, "not a flaplag --json output");
  const std::string command = j["command"].get<std::string>();
  if (command != "map" && command != "study")
    refuse(file, "a flaplag " + command + " result, not a part of a map or study");
  if (!j.contains("shard") || !j["shard"].is_object())
    refuse(file, "a whole flaplag " + command + " result (no \"shard\"), not a part");
  const Json& s = j["shard"];
  p.index = count_of(s, "index", file);
  p.count = count_of(s, "count", file);
  p.first = count_of(s, "first", file);
  p.last = count_of(s, "last", file);
  p.total = count_of(s, "total", file);
  p.axis = s.contains("axis") && s["axis"].is_string() ? s["axis"].get<std::string>() : "";
  const bool axis_ok = command == "study" ? p.axis == "vary" : (p.axis == "x" || p.axis == "y");
  if (!axis_ok || p.index < 1 || p.index > p.count || p.first > p.last || p.last > p.total ||
      p.count > kMaxCount || p.total > kMaxCount)
    refuse(file, "damaged part: inconsistent \"shard\" object");
  const std::string status = j.value("status", "");
  if (status == "cancelled")
    refuse(file, "an interrupted part (status cancelled): run part " + std::to_string(p.index) +
                     "/" + std::to_string(p.count) + " again");
  if (status != "ok" && status != "warning" && status != "failed")
    refuse(file, "damaged part: no valid \"status\"");
  // The data must have the block's shape.
  const std::size_t n = p.last - p.first;
  try {
    const Json& values = axis_values(p);
    bool ok = values.is_array() && values.size() == n;
    if (command == "map") {
      const std::size_t rows = j.at("y").at("values").size();
      for (const std::string& key : data_keys(command)) {
        const Json& d = j.at(key);
        ok = ok && d.is_array() && d.size() == rows;
        for (const Json& row : d)
          ok = ok && row.is_array() && row.size() == j.at("x").at("values").size();
      }
    }
    if (!ok) refuse(file, "damaged part: the data do not match its block of lines");
  } catch (const Json::exception&) {
    refuse(file, "damaged part: the data do not match its block of lines");
  }
  return p;
}

// What must be the same in all parts: everything but the block, its data and its status.
Json case_part(const Part& p) {
  Json j = p.json;
  j.erase("shard");
  j.erase("status");
  j.erase("message");
  for (const std::string& key : data_keys(j["command"].get<std::string>())) j.erase(key);
  if (p.axis == "x" || p.axis == "y") j[p.axis].erase("values");
  if (j.contains("case") && j["case"].is_object()) j["case"].erase("shard");
  return j;
}

// The first key in which a and b differ, as a path ("parameters.theta").
std::string first_difference(const Json& a, const Json& b, const std::string& path = "") {
  for (const auto& [key, value] : a.items()) {
    const std::string at = path.empty() ? key : path + "." + key;
    if (!b.contains(key)) return at;
    if (b[key] == value) continue;
    if (value.is_object() && b[key].is_object()) return first_difference(value, b[key], at);
    return at;
  }
  for (const auto& [key, value] : b.items())
    if (!a.contains(key)) return path.empty() ? key : path + "." + key;
  return path.empty() ? "a key" : path;
}

std::string part_name(std::size_t index, std::size_t count) {
  return std::to_string(index) + "/" + std::to_string(count);
}

}  // namespace

ShardBlock shard_block(const Request& r) {
  ShardBlock b;
  const std::vector<double>* values = &r.vary_values;
  b.axis = "vary";
  if (r.command == Command::Map) {
    const bool columns = r.y_name == "mu";
    b.axis = columns ? "x" : "y";
    values = columns ? &r.x_values : &r.y_values;
  }
  if (r.shard_count > 0)
    block_of(values->size(), static_cast<std::size_t>(r.shard_index),
             static_cast<std::size_t>(r.shard_count), b);
  else
    block_of(values->size(), 1, 1, b);
  return b;
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
  const ShardBlock b = shard_block(r);
  return Json{{"index", r.shard_index}, {"count", r.shard_count}, {"axis", b.axis},
              {"first", b.first},       {"last", b.last},         {"total", b.total}};
}

std::string merge_parts(const Request& r) {
  std::vector<Part> parts;
  for (const std::string& file : r.inputs) parts.push_back(read_part(file));
  const Part& head = parts.front();
  const Json reference = case_part(head);
  std::map<std::size_t, const Part*> by_index;
  for (const Part& p : parts) {
    if (p.count != head.count)
      refuse(p.file, "part " + part_name(p.index, p.count) + ", but " + head.file +
                         " is a part of " + std::to_string(head.count));
    if (p.json["command"] != head.json["command"])
      refuse(p.file, "a part of a " + p.json["command"].get<std::string>() + ", but " + head.file +
                         " is a part of a " + head.json["command"].get<std::string>());
    const Json c = case_part(p);
    if (c != reference || p.total != head.total || p.axis != head.axis)
      refuse(p.file, "not a part of the same case as " + head.file + " (" +
                         (p.total != head.total ? std::string("another number of lines")
                                                : first_difference(reference, c)) +
                         " differs)");
    const auto [it, fresh] = by_index.emplace(p.index, &p);
    if (!fresh)
      refuse(p.file,
             "part " + part_name(p.index, p.count) + " again (also " + it->second->file + ")");
    // The block must be the one of its index (as flaplag computes it).
    ShardBlock b;
    block_of(p.total, p.index, p.count, b);
    if (b.first != p.first || b.last != p.last)
      refuse(p.file, "damaged part: part " + part_name(p.index, p.count) + " is not lines " +
                         std::to_string(b.first) + ".." + std::to_string(b.last));
  }
  std::string missing;
  for (std::size_t i = 1; i <= head.count; ++i)
    if (by_index.count(i) == 0) missing += (missing.empty() ? "" : ", ") + part_name(i, head.count);
  if (!missing.empty()) {
    std::string given;
    for (const auto& [i, p] : by_index)
      given += (given.empty() ? "" : ", ") + p->file + " = " + part_name(i, head.count);
    throw InvalidInput("argument", "(missing)",
                       "part" + std::string(missing.find(',') == std::string::npos ? " " : "s ") +
                           missing + " missing (given: " + given + ")");
  }
  // The first part's document without its "shard", the data of all parts in order.
  Json out = head.json;
  out.erase("shard");
  if (out.contains("case") && out["case"].is_object()) out["case"].erase("shard");
  const std::string command = out["command"].get<std::string>();
  std::string status = "ok", message;
  for (const std::string& key : data_keys(command)) {
    if (head.axis != "x") out[key] = Json::array();
    for (Json& row : out[key])
      if (head.axis == "x") row = Json::array();
  }
  if (head.axis != "vary") out[head.axis]["values"] = Json::array();
  for (const auto& [i, p] : by_index) {
    const Json& j = p->json;
    for (const std::string& key : data_keys(command)) {
      if (head.axis == "x") {
        for (std::size_t row = 0; row < out[key].size(); ++row)
          for (const Json& cell : j[key][row]) out[key][row].push_back(cell);
      } else {
        for (const Json& row : j[key]) out[key].push_back(row);
      }
    }
    if (head.axis != "vary")
      for (const Json& v : j[head.axis]["values"]) out[head.axis]["values"].push_back(v);
    // As the library reports a whole run: the worst status, the first problem met (in line
    // order, so in the first part that has one).
    const std::string s = j["status"].get<std::string>();
    if (status_rank(s) > status_rank(status)) status = s;
    if (message.empty() && j.contains("message") && j["message"].is_string())
      message = j["message"].get<std::string>();
  }
  out["status"] = status;
  out["message"] = message;
  check_merged_output(r, out);  // the text's size against --memory-limit, before making it
  return out.dump(2) + "\n";
}

}  // namespace flaplag::cli
