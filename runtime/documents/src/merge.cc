// flaplag documents — the parts of a batch job and their merge.
#include "flaplag/documents/merge.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <system_error>
#include <utility>
#include <vector>

#include "flaplag/core/errors.h"
#include "flaplag/core/status.h"
#include "flaplag/documents/digest.h"
#include "flaplag/documents/read_file.h"
#include "flaplag/limits.h"
#include "flaplag/model_api.h"

namespace flaplag::documents {

namespace {

using Json = nlohmann::ordered_json;

// The keys that hold the values of the split lines: they differ from part to part.
std::vector<std::string> data_keys(const std::string& command) {
  if (command == "study") return {"rows"};
  return {"max_zeta", "mode", "kind"};
}

// Far above any real job (a map has at most 10000 lines, a study 100000 values); a larger
// number in a file is damage, not a job.
constexpr std::size_t kMaxCount = 100000;

int status_rank(const std::string& s) { return s == "ok" ? 0 : s == "warning" ? 1 : 2; }

struct Part {
  std::string file;  // as typed
  Json json;
  std::size_t index = 0, count = 0, first = 0, last = 0, total = 0;
  std::string axis;
  PartCase request;  // what its case asks for
};

// A part, read within what the parts before it left of the memory limit's JSON budget
// (*budget: bytes, json_read_limit(memory limit) for the first part), so that the parts
// together cannot take more memory than the limit.
Json read_json(const std::string& file, std::uint64_t memory_limit, std::size_t* budget,
               const Spelling& option) {
  Json j;
  std::string error;
  const std::string limit = option("memory_limit");
  const std::string text = read_text_file(
      file, *budget, "part", "cannot be read",
      " (with the parts before it) under " + limit + " " + memory_text(memory_limit) +
          ", which reading JSON of this size may need: raise " + limit);
  *budget -= text.size();
  const JsonParse parsed = parse_json(text, &j, &error);
  if (parsed == JsonParse::NotJson)
    refuse_file(file, "not JSON (a part is the " + option("json") +
                          " output of flaplag map or study with " + option("shard") + ")");
  if (parsed == JsonParse::Refused) refuse_file(file, "damaged part: " + error);
  return j;
}

std::size_t count_of(const Json& shard, const char* key, const std::string& file) {
  const auto it = shard.find(key);
  if (it == shard.end() || !it->is_number_unsigned())
    refuse_file(file, std::string("damaged part: \"shard\" has no whole number \"") + key + "\"");
  return it->get<std::size_t>();
}

// The text a digest is computed over: the document without the digest, compact, keys in the
// order written (parse and dump give back the same text for every value flaplag writes).
std::string digested_text(Json j) {
  j["shard"].erase("digest");
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

const char* const kDigestPrefix = "sha256:";

// The exact text of a JSON value, for comparisons that tell 1 from 1.0 and 0.0 from -0.0.
std::string exact(const Json& v) { return v.dump(); }

// The mode labels of a model with M flap and N lag modes (model_api.h: flap, flap2, ..., lag, ...).
std::vector<std::string> mode_labels(const Json& model) {
  std::vector<std::string> labels;
  for (const char* kind : model::kDirectionNames) {
    const std::size_t count = model.at(std::string(kind) + "_modes").get<std::size_t>();
    for (std::size_t i = 1; i <= count && i <= 1000; ++i)
      labels.push_back(model::mode_label(kind, static_cast<int>(i)));
  }
  return labels;
}

bool one_of(const Json& v, const std::vector<std::string>& names) {
  return v.is_string() &&
         std::find(names.begin(), names.end(), v.get<std::string>()) != names.end();
}

const std::vector<std::string>& kind_names() {
  static const std::vector<std::string> names = {kind_name(InstabilityKind::Flutter),
                                                 kind_name(InstabilityKind::Periodic)};
  return names;
}

const std::vector<std::string>& status_names() {
  static const std::vector<std::string> names = {
      status_name(Status::Ok), status_name(Status::Warning), status_name(Status::Failed)};
  return names;
}

bool number_or_null(const Json& v) { return v.is_null() || v.is_number(); }

// What the part's case asks for: what the part claims to have computed.
PartCase request_of(const std::string& file, const Json& j, const PartCases& cases) {
  const auto c = j.find("case");
  if (c == j.end() || !c->is_object()) refuse_file(file, "damaged part: no \"case\" object");
  try {
    return cases.read(file, *c);
  } catch (const InvalidInput& e) {
    refuse_file(file, std::string("damaged part: its case is not a command flaplag takes (") +
                          e.what() + ")");
  }
}

Part read_part(const std::string& file, std::uint64_t memory_limit, std::size_t* budget,
               const PartCases& cases, const Spelling& option) {
  Part p;
  p.file = file;
  p.json = read_json(file, memory_limit, budget, option);
  const Json& j = p.json;
  if (!j.is_object() || !j.contains("flaplag") || !j.contains("command") ||
      !j["command"].is_string())
    refuse_file(file, "not a flaplag " + option("json") + " output");
  const std::string command = j["command"].get<std::string>();
  if (command != "map" && command != "study")
    refuse_file(file, "a flaplag " + command + " result, not a part of a map or study");
  if (!j.contains("shard") || !j["shard"].is_object())
    refuse_file(file, "a whole flaplag " + command + " result (no \"shard\"), not a part");
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
    refuse_file(file, "damaged part: inconsistent \"shard\" object");
  const auto status = j.find("status");
  if (status == j.end() || !status->is_string())
    refuse_file(file, "damaged part: no valid \"status\"");
  if (*status == "cancelled")
    refuse_file(file, "an interrupted part (status cancelled): run part " +
                          std::to_string(p.index) + "/" + std::to_string(p.count) + " again");
  if (!one_of(*status, status_names())) refuse_file(file, "damaged part: no valid \"status\"");
  if (j.contains("message") && !j["message"].is_string())
    refuse_file(file, "damaged part: \"message\" is not text");
  // The digest of what flaplag wrote: any later change to the file shows.
  const auto digest = s.find("digest");
  if (digest == s.end() || !digest->is_string())
    refuse_file(file, "a part without a digest (written by another flaplag, or edited): run part " +
                          std::to_string(p.index) + "/" + std::to_string(p.count) + " again");
  if (digest->get<std::string>() != kDigestPrefix + sha256_hex(digested_text(j)))
    refuse_file(file,
                "damaged part: its data do not match its digest (the file was changed after "
                "flaplag wrote it)");
  // What its case asks for, and the block it says it is.
  p.request = request_of(file, j, cases);
  const PartCase& r = p.request;
  if (r.command != command || !r.json || r.index != p.index || r.count != p.count)
    refuse_file(file, "damaged part: its \"shard\" or \"command\" is not what its case asks for");
  const ShardBlock& b = r.block;
  if (b.axis != p.axis || b.first != p.first || b.last != p.last || b.total != p.total)
    refuse_file(file, "damaged part: part " + std::to_string(p.index) + "/" +
                          std::to_string(p.count) + " of its case is lines " +
                          std::to_string(b.first) + ".." + std::to_string(b.last) + " of " +
                          std::to_string(b.total) + " (" + b.axis +
                          "), not what its \"shard\" says");
  return p;
}

// The data of a part against what its case computes: the axis values of its block (exactly as
// flaplag writes them), the shapes of its arrays, and each cell's type and vocabulary (labels
// of the case's model, kinds, statuses).  `model` is the case's model (checked against the case).
void check_data(const Part& p, const Json& model) {
  const Json& j = p.json;
  const PartCase& block = p.request;
  const std::vector<std::string> labels = mode_labels(model);
  auto fail = [&p](const std::string& what) {
    refuse_file(p.file, "damaged part: " + what + " is not what its case computes");
  };
  auto same_values = [](const Json& values, const std::vector<double>& expected) {
    if (!values.is_array() || values.size() != expected.size()) return false;
    for (std::size_t i = 0; i < expected.size(); ++i)
      if (exact(values[i]) != exact(Json(expected[i]))) return false;
    return true;
  };
  if (p.axis == "vary") {
    const Json& rows = j.at("rows");
    if (!rows.is_array() || rows.size() != block.vary.size()) fail("the number of rows");
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Json& row = rows[k];
      const std::string at = "row " + std::to_string(k + 1);
      if (!row.is_object()) fail(at);
      if (exact(row.at("value")) != exact(Json(block.vary[k]))) fail(at + " value");
      const bool found = !row.at("mode").is_null();
      bool ok = row.at("hover_unstable").is_boolean() && number_or_null(row.at("mu_c")) &&
                number_or_null(row.at("mu_c_error")) && number_or_null(row.at("omega")) &&
                (!row.contains("basis_error") || number_or_null(row["basis_error"])) &&
                (found ? one_of(row["mode"], labels) : row.at("mu_c").is_null()) &&
                (found ? one_of(row.at("kind"), kind_names()) : row.at("kind").is_null()) &&
                one_of(row.at("status"), status_names()) && row.at("message").is_string() &&
                row.at("intervals").is_array() &&
                (!row.contains("trim") || row["trim"].is_null() || row["trim"].is_object());
      for (const Json& iv : row.at("intervals"))
        ok = ok && iv.is_array() && iv.size() == 2 && iv[0].is_number() && number_or_null(iv[1]);
      if (!ok) fail(at);
    }
    return;
  }
  if (!same_values(j.at("x").at("values"), block.x)) fail("x.values");
  if (!same_values(j.at("y").at("values"), block.y)) fail("y.values");
  const std::size_t rows = block.y.size(), columns = block.x.size();
  for (const std::string& key : data_keys("map")) {
    const Json& d = j.at(key);
    if (!d.is_array() || d.size() != rows) fail("the shape of " + key);
    for (const Json& row : d)
      if (!row.is_array() || row.size() != columns) fail("the shape of " + key);
  }
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t k = 0; k < columns; ++k) {
      const Json& zeta = j["max_zeta"][i][k];
      const Json& mode = j["mode"][i][k];
      const Json& kind = j["kind"][i][k];
      // A cell without a result is null in all three; a zeta that is not finite is null or
      // "-inf" beside its mode and kind.
      const bool ok = mode.is_null() ? zeta.is_null() && kind.is_null()
                                     : one_of(mode, labels) && one_of(kind, kind_names()) &&
                                           (zeta.is_number() || zeta.is_null() || zeta == "-inf");
      if (!ok)
        fail("the cell (" + std::to_string(i + 1) + ", " + std::to_string(k + 1) +
             ") of max_zeta, mode and kind");
    }
  }
}

// What must be the same in all parts: everything but the block, its data and its status.
Json case_part(const Json& part, const std::string& axis) {
  Json j = part;
  j.erase("shard");
  j.erase("status");
  j.erase("message");
  for (const std::string& key : data_keys(j["command"].get<std::string>())) j.erase(key);
  if ((axis == "x" || axis == "y") && j.contains(axis) && j[axis].is_object())
    j[axis].erase("values");
  if (j.contains("case") && j["case"].is_object()) j["case"].erase("shard");
  return j;
}

// The first key in which a and b differ, as a path ("parameters.theta").
std::string first_difference(const Json& a, const Json& b, const std::string& path = "") {
  for (const auto& [key, value] : a.items()) {
    const std::string at = path.empty() ? key : path + "." + key;
    if (!b.contains(key)) return at;
    if (exact(b[key]) == exact(value)) continue;
    if (value.is_object() && b[key].is_object()) return first_difference(value, b[key], at);
    return at;
  }
  for (const auto& [key, value] : b.items())
    if (!a.contains(key)) return path.empty() ? key : path + "." + key;
  return path.empty() ? "a key" : path;
}

// The part of a case's output that does not depend on the lines computed: the command run on no
// lines (the model, method, parameters, the names and the other axis of a map, ...).
Json skeleton(const Part& p, const PartCases& cases) {
  try {
    return cases.skeleton(p.file, p.json.at("case"), p.axis);
  } catch (const InvalidInput& e) {
    refuse_file(p.file, std::string("damaged part: its case is not a command flaplag takes (") +
                            e.what() + ")");
  }
}

std::string part_name(std::size_t index, std::size_t count) {
  return std::to_string(index) + "/" + std::to_string(count);
}

// The parts joined in line order: the first part's document without its "shard", the data of
// all parts in order, the worst status and the first message.  The text's size is checked
// against the memory limit before it is made.
std::string assemble(const std::vector<std::string>& files, std::uint64_t memory_limit,
                     const Part& head, const std::map<std::size_t, const Part*>& by_index) {
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
  check_merged_size(files, memory_limit, out);
  return out.dump(2) + "\n";
}

// The length of j.dump(2): containers laid out as nlohmann::json does (one element per line,
// two spaces per level), each scalar as its own dump.  Iterative: no recursion on nesting.
std::uint64_t json_text_size(const nlohmann::ordered_json& root) {
  std::uint64_t total = 0;
  std::vector<std::pair<const nlohmann::ordered_json*, std::uint64_t>> stack{{&root, 0}};
  while (!stack.empty()) {
    const auto [j, depth] = stack.back();
    stack.pop_back();
    if (!j->is_structured()) {
      total += j->dump().size();
      continue;
    }
    const std::uint64_t n = j->size();
    if (n == 0) {
      total += 2;  // [] or {}
      continue;
    }
    // "[\n", each element on a line of its own indented by 2 (depth + 1) and ended by ",\n"
    // (the last by "\n"), then the closing bracket indented by 2 depth.
    total += 2 + n * (2 * (depth + 1) + 2) - 1 + 2 * depth + 1;
    if (j->is_object()) {
      for (auto it = j->begin(); it != j->end(); ++it) {
        total += nlohmann::ordered_json(it.key()).dump().size() + 2;  // "key":
        stack.emplace_back(&it.value(), depth + 1);
      }
    } else {
      for (const auto& e : *j) stack.emplace_back(&e, depth + 1);
    }
  }
  return total;
}

}  // namespace

ShardBlock block_of(const char* axis, std::size_t total, std::size_t index, std::size_t count) {
  ShardBlock b;
  b.axis = axis;
  b.total = total;
  b.first = total * (index - 1) / count;
  b.last = total * index / count;
  return b;
}

Json shard_json(const ShardBlock& b, std::size_t index, std::size_t count) {
  return Json{{"index", index},   {"count", count}, {"axis", b.axis},
              {"first", b.first}, {"last", b.last}, {"total", b.total}};
}

void seal_part(Json& j) { j["shard"]["digest"] = kDigestPrefix + sha256_hex(digested_text(j)); }

std::string merge_parts(const std::vector<std::string>& files, std::uint64_t memory_limit,
                        const PartCases& cases, const Spelling& option) {
  std::vector<Part> parts;
  std::size_t budget = json_read_limit(memory_limit);
  for (const std::string& file : files)
    parts.push_back(read_part(file, memory_limit, &budget, cases, option));
  const Part& head = parts.front();
  // The first part against what its case computes; the others against the first.
  const Json reference = case_part(head.json, head.axis);
  {
    Json expected = case_part(skeleton(head, cases), head.axis), got = reference;
    for (Json* j : {&expected, &got}) {
      j->erase("flaplag");
      j->erase("case");
    }
    if (exact(got) != exact(expected))
      refuse_file(head.file, "damaged part: " + first_difference(expected, got) +
                                 " is not what its case computes");
  }
  std::map<std::size_t, const Part*> by_index;
  for (const Part& p : parts) {
    if (p.count != head.count)
      refuse_file(p.file, "part " + part_name(p.index, p.count) + ", but " + head.file +
                              " is a part of " + std::to_string(head.count));
    if (p.json["command"] != head.json["command"])
      refuse_file(p.file, "a part of a " + p.json["command"].get<std::string>() + ", but " +
                              head.file + " is a part of a " +
                              head.json["command"].get<std::string>());
    const Json c = case_part(p.json, p.axis);
    if (exact(c) != exact(reference) || p.total != head.total || p.axis != head.axis)
      refuse_file(p.file, "not a part of the same case as " + head.file + " (" +
                              (p.total != head.total ? std::string("another number of lines")
                                                     : first_difference(reference, c)) +
                              " differs)");
    const auto [it, fresh] = by_index.emplace(p.index, &p);
    if (!fresh)
      refuse_file(p.file,
                  "part " + part_name(p.index, p.count) + " again (also " + it->second->file + ")");
    try {
      check_data(p, head.json.at("model"));
    } catch (const Json::exception&) {
      refuse_file(p.file, "damaged part: a key is missing or has the wrong type");
    }
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
  // Every part checked: the merged file is head.total lines of the case's grid.
  return assemble(files, memory_limit, head, by_index);
}

void check_merged_size(const std::vector<std::string>& files, std::uint64_t memory_limit,
                       const Json& merged) {
  const std::uint64_t text = json_text_size(merged) + 1;  // and the final newline
  const MemoryEstimate e = json_output_memory(text);
  if (e.memory <= memory_limit) return;
  std::uint64_t parts = 0;
  for (const std::string& file : files) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (!ec) parts += size;
  }
  std::string reason = "the merged output of " + std::to_string(files.size()) + " part" +
                       (files.size() == 1 ? "" : "s") + " (" + memory_text(parts) + ") would be " +
                       memory_text(text) + " of JSON, needing about " + memory_text(e.memory) +
                       " of memory, more than the memory limit of " + memory_text(memory_limit) +
                       " (`memory_limit`)";
  if (text > 4 * parts + 65536)
    reason +=
        ": parts written by flaplag are as large as their merge, so a part was not made by "
        "flaplag; raise `memory_limit` only for parts you trust";
  else
    reason += ": raise `memory_limit`";
  throw InvalidInput("memory_limit", memory_text(memory_limit), reason);
}

}  // namespace flaplag::documents
