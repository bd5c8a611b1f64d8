#include "raw_volume_options.hpp"

#include "numbers.hpp"
#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"

namespace pss::app {

void add_raw_volume_options(CLI::App& command, RawVolumeOptions& o) {
  command.add_option("--dims", o.dims, "raw volume size XxYxZ, x fastest")
      ->check(parsed_by(parse_dims, "--dims", "XxYxZ"));
  command.add_option("--type", o.type, "raw voxel type (default uint8)")
      ->check(CLI::IsMember({"int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"}));
  command.add_option("--spacing", o.spacing, "raw voxel spacing sx,sy,sz (default 1,1,1)")
      ->check(parsed_by(parse_spacing, "--spacing", "SX,SY,SZ"));
  command.add_option("--endian", o.endian, "raw byte order of multi-byte voxels (default little)")
      ->check(CLI::IsMember({"little", "big"}));
  command.add_option("--skip", o.skip, "raw header bytes before the voxels (default 0): the file holds BYTES + voxels")
      ->check(parsed_by(parse_skip, "--skip", "BYTES"));
}

std::optional<RawVolumeFormat> raw_volume_format(const RawVolumeOptions& o, const std::string& input) {
  if (o.dims.empty() && o.type.empty() && o.spacing.empty() && o.endian.empty() && o.skip.empty()) return std::nullopt;
  if (is_point_cloud_file(input))
    throw Error(input + ": a point cloud, not a volume; --dims/--type/--spacing/--endian/--skip describe a raw volume");
  if (has_volume_header(input))
    throw Error(input + ": the file's header describes the volume; drop --dims/--type/--spacing/--endian/--skip");
  if (o.dims.empty()) throw Error("a raw volume needs --dims XxYxZ");
  RawVolumeFormat f;
  f.dims = parse_dims(o.dims);
  if (!o.type.empty()) f.type = parse_voxel_type(o.type);
  if (!o.spacing.empty()) f.spacing = parse_spacing(o.spacing);
  if (!o.skip.empty()) f.skip = parse_skip(o.skip);
  f.big_endian = o.endian == "big";
  return f;
}

}  // namespace pss::app
