// flaplag Python module — the documents layer: the report of a result file and the merge of the
// --shard parts of a map or study, as `flaplag report` and `flaplag merge` make them.
//
// A result file and a part are the command line's JSON outputs, and a part's case is a command
// line: the merge reads it as the command line does (cli/shard.h), so that a part Python accepts
// is one `flaplag merge` accepts and the merged text is the same bytes.  The documents layer
// names the arguments it refuses by field; here they are the keyword arguments of flaplag.report
// and flaplag.merge, and the options of a result's case keep the command line's spelling.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "flaplag/core/errors.h"
#include "flaplag/documents/merge.h"
#include "flaplag/documents/output.h"
#include "flaplag/documents/read_file.h"
#include "flaplag/documents/report.h"
#include "shard.h"

namespace py = pybind11;

namespace flaplag::python {
namespace {

// The command line's options a result file speaks of (it is the command line's --json output);
// every other field is a keyword argument here.
std::string python_spelling(std::string_view field) {
  if (field == "json" || field == "shard" || field == "plot") return "--" + std::string(field);
  return std::string(field);
}

// The options of a result's case, in the command line that reproduces it.
std::string case_spelling(std::string_view key) { return "--" + std::string(key); }

// Runs `make` with a refused file (InvalidInput "argument") named by the keyword argument that
// gave it.
template <class Make>
std::string naming(const char* argument, Make&& make) {
  try {
    return make();
  } catch (const InvalidInput& e) {
    if (e.name() != "argument") throw;
    throw InvalidInput(argument, e.value(), e.reason());
  }
}

std::string report_file(const std::string& result, const std::string& html,
                        std::uint64_t memory_limit) {
  // The page's path is checked before the result is read: a page that cannot be written leaves
  // no work done for nothing.
  const documents::OutputTarget page(html, "html");
  const std::string text = naming("result", [&] {
    return documents::read_json_file(result, memory_limit, "result file", "cannot be read",
                                     python_spelling);
  });
  const std::string page_text = naming("result", [&] {
    return documents::html_report_of_text(result, text, python_spelling, case_spelling);
  });
  if (!html.empty()) page.write(page_text);
  return page_text;
}

std::string merge_files(const std::vector<std::string>& parts, const std::string& output,
                        std::uint64_t memory_limit) {
  if (parts.empty()) throw InvalidInput("parts", "[]", "no parts given");
  const documents::OutputTarget target(output, "output");
  const std::string text = naming("parts", [&] {
    return documents::merge_parts(parts, memory_limit, cli::command_line_cases(), python_spelling);
  });
  if (!output.empty()) target.write(text);
  return text;
}

}  // namespace

void bind_documents(py::module_& m) {
  m.def("report", &report_file, py::arg("result"), py::arg("html"), py::arg("memory_limit"),
        "The HTML page of a result file (flaplag report RESULT.json); written to html unless "
        "it is empty.");
  m.def("merge", &merge_files, py::arg("parts"), py::arg("output"), py::arg("memory_limit"),
        "The --shard parts of a map or study as one result (flaplag merge PART...); written to "
        "output unless it is empty.");
}

}  // namespace flaplag::python
