#include "src/hdf5_writer.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "src/atomic_file.hpp"

namespace mpsolid {

namespace {
void check(herr_t status, const char* what) {
  if (status < 0) throw std::runtime_error(fmt::format("HDF5 error while writing {}", what));
}
hid_t check_id(hid_t id, const char* what) {
  if (id < 0) throw std::runtime_error(fmt::format("HDF5 error while creating {}", what));
  return id;
}

template <class T>
hid_t h5_type();
template <>
hid_t h5_type<double>() {
  return H5T_NATIVE_DOUBLE;
}
template <>
hid_t h5_type<std::int32_t>() {
  return H5T_NATIVE_INT32;
}
template <>
hid_t h5_type<std::int8_t>() {
  return H5T_NATIVE_INT8;
}
template <>
hid_t h5_type<std::int64_t>() {
  return H5T_NATIVE_INT64;
}

template <class T>
void write_dataset(hid_t where, const char* name, const std::vector<T>& data, hsize_t columns = 1) {
  const hsize_t dims[2] = {data.size() / columns, columns};
  const hid_t space = check_id(H5Screate_simple(columns == 1 ? 1 : 2, dims, nullptr), name);
  const hid_t set = check_id(
      H5Dcreate2(where, name, h5_type<T>(), space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), name);
  check(H5Dwrite(set, h5_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), name);
  H5Dclose(set);
  H5Sclose(space);
}

template <class T>
void write_attribute(hid_t where, const char* name, T value) {
  const hid_t space = check_id(H5Screate(H5S_SCALAR), name);
  const hid_t attr =
      check_id(H5Acreate2(where, name, h5_type<T>(), space, H5P_DEFAULT, H5P_DEFAULT), name);
  check(H5Awrite(attr, h5_type<T>(), &value), name);
  H5Aclose(attr);
  H5Sclose(space);
}

void write_strings(hid_t where, const char* name, const std::vector<std::string>& items) {
  std::size_t width = 1;
  for (const auto& s : items) width = std::max(width, s.size() + 1);
  std::vector<char> buffer(width * items.size(), '\0');
  for (std::size_t k = 0; k < items.size(); ++k)
    std::copy(items[k].begin(), items[k].end(), buffer.begin() + static_cast<long>(k * width));
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, width);
  const hsize_t dims[1] = {items.size()};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t set =
      check_id(H5Dcreate2(where, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), name);
  check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), name);
  H5Dclose(set);
  H5Sclose(space);
  H5Tclose(type);
}
}  // namespace

struct FrameWriter::File {
  hid_t file = -1;
  hid_t frames = -1;
  std::vector<std::size_t> storage_of_id;
};

FrameWriter::FrameWriter(const std::filesystem::path& path, const Simulation& sim)
    : path_(path), file_(std::make_unique<File>()) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by exceptions
  file_->file = check_id(
      H5Fcreate(staging_path(path).c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "frames.h5");
  file_->frames =
      check_id(H5Gcreate2(file_->file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "frames");
  file_->storage_of_id = sim.particles().storage_of_id();
  std::vector<std::string> bodies;
  for (const auto& b : sim.spec().bodies) bodies.push_back(b.name);
  write_strings(file_->file, "body_names", bodies);
  write_strings(file_->file, "kind_names", {"wall", "elastic", "rigid"});
  write_attribute<double>(file_->file, "l0", sim.spec().l0);
  write_attribute<double>(file_->file, "depth", sim.spec().depth);
}

FrameWriter::~FrameWriter() {
  if (file_ && file_->file >= 0) {
    H5Gclose(file_->frames);
    H5Fclose(file_->file);
  }
}

void FrameWriter::write(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  const auto& order = file_->storage_of_id;
  const std::string name = fmt::format("{:06d}", frames_);
  const hid_t group = check_id(
      H5Gcreate2(file_->frames, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "frame");
  write_attribute<std::int64_t>(group, "step", sim.step());
  write_attribute<double>(group, "time", sim.time());

  const std::size_t n = p.size();
  auto gather = [&](const std::vector<double>& field) {
    std::vector<double> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = field[order[k]];
    return out;
  };
  auto gather_pair = [&](const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> out(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
      out[2 * k] = a[order[k]];
      out[2 * k + 1] = b[order[k]];
    }
    return out;
  };
  std::vector<std::int32_t> id(n), body(n);
  std::vector<std::int8_t> kind(n);
  for (std::size_t k = 0; k < n; ++k) {
    id[k] = p.id[order[k]];
    body[k] = p.body[order[k]];
    kind[k] = static_cast<std::int8_t>(p.kind[order[k]]);
  }
  write_dataset(group, "id", id);
  write_dataset(group, "kind", kind);
  write_dataset(group, "body", body);
  write_dataset(group, "position", gather_pair(p.x, p.y), 2);
  write_dataset(group, "velocity", gather_pair(p.vx, p.vy), 2);
  write_dataset(group, "rotation", gather(p.theta));
  write_dataset(group, "angular_velocity", gather(p.omega));
  write_dataset(group, "volumetric_strain", gather(p.strain));
  write_dataset(group, "pressure", gather(p.pressure));
  H5Gclose(group);
  H5Fflush(file_->file, H5F_SCOPE_GLOBAL);  // a crashed run keeps its frames
  ++frames_;
}

std::uintmax_t FrameWriter::bytes_written() const {
  if (file_->file < 0) return published_bytes_;
  hsize_t size = 0;
  H5Fget_filesize(file_->file, &size);
  return size;
}

void FrameWriter::publish() {
  published_bytes_ = bytes_written();
  H5Gclose(file_->frames);
  H5Fclose(file_->file);
  file_->file = -1;
  publish_staged_file(path_);
}

}  // namespace mpsolid
