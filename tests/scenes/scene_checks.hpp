// Small checks shared by the scene tests: a strict JSON parser (run.json, timings.json), the entries
// of a .pvd collection, the files of a directory, and the signs of a crash in a program's output.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace loom::testing {

// A parsed JSON value. parse_json throws std::runtime_error (with the offset) on anything that is not
// one complete JSON value: the writer of run.json is hand-written, so the test checks the syntax too.
struct Json {
  enum class Kind { null, boolean, number, string, array, object } kind = Kind::null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> array;
  std::map<std::string, Json> object;

  bool has(const std::string& key) const { return kind == Kind::object && object.count(key) > 0; }
  const Json& at(const std::string& key) const;
};
Json parse_json(const std::string& text);

// <DataSet timestep="..." file="..."/> entries of a .pvd, in file order. Throws if the text is not a
// VTKFile of type Collection with a closed <Collection> element.
struct PvdEntry {
  double time = 0.0;
  std::string file;
};
std::vector<PvdEntry> parse_pvd(const std::string& text);

// Names of the regular files under `dir`, recursively, relative to it, sorted.
std::vector<std::string> files_under(const std::string& dir);

// A message that says the program crashed or hit a programming error instead of reporting bad input.
bool looks_like_crash(const std::string& stderr_text);
// stderr without the scene's warning lines ("file:line:column: warning: ..."), e.g. p1 at nu > 0.49.
std::string without_warnings(const std::string& stderr_text);

}  // namespace loom::testing
