#include "script.hpp"

#include <fstream>
#include <map>
#include <sstream>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"

namespace pss::app::view {

std::vector<Step> read_script(const std::string& path) {
  // Verb → its number of arguments.
  static const std::map<std::string, std::size_t> arity{{"view", 2}, {"zoom", 1}, {"pan", 2},   {"fov", 1},
                                                        {"camera", 1}, {"set", 2}, {"wait", 0}, {"screenshot", 1}, {"window", 1},
                                                        {"quit", 0}};
  std::ifstream in(path);
  if (!in) throw file_error(path, "cannot read the script");
  std::vector<Step> steps;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (line > 100000) throw file_error(path, "too many lines for a script");
    text = text.substr(0, text.find('#'));
    std::istringstream words(text);
    Step step;
    step.line = line;
    if (!(words >> step.verb)) continue;
    for (std::string w; words >> w;) step.args.push_back(w);
    const auto known = arity.find(step.verb);
    const std::string where = path + ":" + std::to_string(line);
    if (known == arity.end()) throw file_error(where, "unknown step " + quote(step.verb));
    if (step.args.size() != known->second)
      throw file_error(where, quote(step.verb) + " takes " + std::to_string(known->second) + " argument(s)");
    steps.push_back(std::move(step));
  }
  return steps;
}

}  // namespace pss::app::view
