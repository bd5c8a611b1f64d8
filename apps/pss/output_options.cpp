#include "output_options.hpp"

#include "pss/core/error.hpp"
#include "pss/io/output_format.hpp"

namespace pss::app {
namespace {

template <class FormatOf>
CLI::Validator output_named_for(FormatOf format_of, const char* type_name) {
  return CLI::Validator(
      [format_of](std::string& path) -> std::string {
        try {
          format_of(path);
        } catch (const Error& e) {
          return e.what();
        }
        return {};
      },
      type_name, type_name);
}

}  // namespace

CLI::Validator image_output() { return output_named_for(image_format_of, "IMAGE"); }
CLI::Validator points_output() { return output_named_for(points_format_of, "POINTS"); }
CLI::Validator mesh_output() { return output_named_for(mesh_format_of, "MESH"); }

}  // namespace pss::app
