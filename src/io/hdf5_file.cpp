#include "src/io/hdf5_file.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <fstream>
#include <type_traits>

namespace mpsolid::h5 {

static_assert(std::is_same_v<hid_t, std::int64_t>, "HDF5 1.10 or later: hid_t is 64-bit");

namespace {

// Closes an HDF5 id of any kind at the end of a scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void silence_hdf5() {
  static const bool done = [] {
    // Every file is closed by its owner. HDF5's own clean-up at exit would
    // close again a file whose close failed (a full disk) and crash in it.
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // failures become exceptions
    return true;
  }();
  (void)done;
}

hid_t checked(hid_t id, const std::string& what) {
  if (id < 0) throw Error(fmt::format("HDF5 error: {}", what));
  return id;
}
void checked_status(herr_t status, const std::string& what) {
  if (status < 0) throw Error(fmt::format("HDF5 error: {}", what));
}

template <class T>
hid_t memory_type() {
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  if constexpr (std::is_same_v<T, std::int8_t>) return H5T_NATIVE_INT8;
  if constexpr (std::is_same_v<T, std::int32_t>) return H5T_NATIVE_INT32;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_NATIVE_UINT64;
}

template <class T>
char type_class_of() {
  if constexpr (std::is_floating_point_v<T>) return 'f';
  if constexpr (std::is_signed_v<T>) return 'i';
  return 'u';
}

// Class and size of a stored type, as in DatasetInfo.
std::pair<char, std::size_t> describe_type(hid_t type) {
  const std::size_t size = H5Tget_size(type);
  switch (H5Tget_class(type)) {
    case H5T_FLOAT:
      return {'f', size};
    case H5T_INTEGER:
      return {H5Tget_sign(type) == H5T_SGN_NONE ? 'u' : 'i', size};
    case H5T_STRING:
      return {'s', size};
    default:
      return {'?', size};
  }
}

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  return 0;
}
}  // namespace

Group::Group(Group&& other) noexcept : id_(other.id_), path_(std::move(other.path_)) {
  other.id_ = -1;
}

Group& Group::operator=(Group&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) H5Gclose(id_);
    id_ = other.id_;
    path_ = std::move(other.path_);
    other.id_ = -1;
  }
  return *this;
}

Group::~Group() {
  if (id_ >= 0) H5Gclose(id_);
}

std::string Group::where(const std::string& name) const {
  return path_.back() == '/' ? path_ + name : path_ + "/" + name;
}

Group Group::create_group(const std::string& name) const {
  return Group(checked(H5Gcreate2(id_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       "cannot create group " + where(name)),
               where(name));
}

Group Group::open_group(const std::string& name) const {
  if (!has(name)) throw Error(fmt::format("{} is missing", where(name)));
  return Group(checked(H5Gopen2(id_, name.c_str(), H5P_DEFAULT), "cannot open " + where(name)),
               where(name));
}

bool Group::has(const std::string& name) const {
  return H5Lexists(id_, name.c_str(), H5P_DEFAULT) > 0;
}

void Group::remove(const std::string& name) const {
  checked_status(H5Ldelete(id_, name.c_str(), H5P_DEFAULT), "cannot delete " + where(name));
}

std::vector<std::string> Group::children() const {
  std::vector<std::string> names;
  checked_status(H5Literate(id_, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names),
                 "cannot list " + path_);
  return names;
}

namespace {
// A dataset of rows x columns of T, deflate-compressed (level > 0, with byte
// shuffling) in chunks of up to kChunkRows rows.
template <class T>
Handle create_dataset(hid_t where_id, const std::string& name, const std::string& where_text,
                      std::size_t rows, std::size_t columns, int deflate) {
  const hsize_t dims[2] = {rows, columns};
  const int rank = columns == 1 ? 1 : 2;
  Handle space(checked(H5Screate_simple(rank, dims, nullptr), "dataspace for " + where_text),
               H5Sclose);
  Handle props(checked(H5Pcreate(H5P_DATASET_CREATE), "properties"), H5Pclose);
  if (deflate > 0 && dims[0] > 0) {
    if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0)
      throw Error("this HDF5 library has no deflate filter (output.compression must be 0)");
    // Chunks of up to 64 Ki rows: whole datasets for ordinary cases.
    const hsize_t chunk[2] = {std::min<hsize_t>(dims[0], kChunkRows), columns};
    checked_status(H5Pset_chunk(props, rank, chunk), "chunking " + where_text);
    checked_status(H5Pset_shuffle(props), "shuffle filter for " + where_text);
    checked_status(H5Pset_deflate(props, static_cast<unsigned>(deflate)),
                   "deflate filter for " + where_text);
  }
  return Handle(checked(H5Dcreate2(where_id, name.c_str(), memory_type<T>(), space, H5P_DEFAULT,
                                   props, H5P_DEFAULT),
                        "cannot create " + where_text),
                H5Dclose);
}
}  // namespace

template <class T>
void Group::write(const std::string& name, const std::vector<T>& data, std::size_t columns,
                  int deflate) const {
  static_assert(kSupported<T>);
  Handle set = create_dataset<T>(id_, name, where(name), data.size() / columns, columns, deflate);
  if (!data.empty())
    checked_status(H5Dwrite(set, memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                   "cannot write " + where(name));
}

template <class T>
void Group::create(const std::string& name, std::size_t rows, std::size_t columns,
                   int deflate) const {
  static_assert(kSupported<T>);
  create_dataset<T>(id_, name, where(name), rows, columns, deflate);
}

template <class T>
void Group::write_rows(const std::string& name, std::size_t first, const std::vector<T>& data,
                       std::size_t columns) const {
  static_assert(kSupported<T>);
  if (data.empty()) return;
  Handle set(checked(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), "cannot open " + where(name)),
             H5Dclose);
  Handle file_space(checked(H5Dget_space(set), "dataspace of " + where(name)), H5Sclose);
  const int rank = columns == 1 ? 1 : 2;
  const hsize_t start[2] = {first, 0};
  const hsize_t count[2] = {data.size() / columns, columns};
  checked_status(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr),
                 "rows of " + where(name));
  Handle memory_space(checked(H5Screate_simple(rank, count, nullptr), "rows' dataspace"), H5Sclose);
  checked_status(
      H5Dwrite(set, memory_type<T>(), memory_space, file_space, H5P_DEFAULT, data.data()),
      "cannot write rows of " + where(name));
}

template <class T>
std::uint64_t Group::reserve(const std::string& name, std::size_t rows, std::size_t columns) const {
  static_assert(kSupported<T>);
  const hsize_t dims[2] = {rows, columns};
  const int rank = columns == 1 ? 1 : 2;
  Handle space(checked(H5Screate_simple(rank, dims, nullptr), "dataspace for " + where(name)),
               H5Sclose);
  Handle props(checked(H5Pcreate(H5P_DATASET_CREATE), "properties"), H5Pclose);
  checked_status(H5Pset_layout(props, H5D_CONTIGUOUS), "layout of " + where(name));
  checked_status(H5Pset_alloc_time(props, H5D_ALLOC_TIME_EARLY), "allocation of " + where(name));
  checked_status(H5Pset_fill_time(props, H5D_FILL_TIME_NEVER), "fill of " + where(name));
  Handle set(checked(H5Dcreate2(id_, name.c_str(), memory_type<T>(), space, H5P_DEFAULT, props,
                                H5P_DEFAULT),
                     "cannot create " + where(name)),
             H5Dclose);
  if (rows == 0) return 0;
  const haddr_t offset = H5Dget_offset(set);
  if (offset == HADDR_UNDEF) throw Error("HDF5 error: no file offset for " + where(name));
  return static_cast<std::uint64_t>(offset);
}

template <class T>
std::optional<std::uint64_t> Group::placed_offset(const std::string& name, std::size_t rows,
                                                  std::size_t columns) const {
  static_assert(kSupported<T>);
  const DatasetInfo stored = info(name);
  const std::vector<std::uint64_t> expected =
      columns == 1 ? std::vector<std::uint64_t>{rows} : std::vector<std::uint64_t>{rows, columns};
  if (stored.dims != expected || !stored.filter.empty()) return std::nullopt;
  if (rows == 0) return 0;
  Handle set(checked(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), "cannot open " + where(name)),
             H5Dclose);
  Handle type(checked(H5Dget_type(set), "type of " + where(name)), H5Tclose);
  if (H5Tequal(type, memory_type<T>()) <= 0) return std::nullopt;  // another byte order or type
  Handle props(checked(H5Dget_create_plist(set), "properties of " + where(name)), H5Pclose);
  if (H5Pget_layout(props) != H5D_CONTIGUOUS) return std::nullopt;
  const haddr_t offset = H5Dget_offset(set);
  if (offset == HADDR_UNDEF) return std::nullopt;  // never written
  return static_cast<std::uint64_t>(offset);
}

DatasetInfo Group::info(const std::string& name) const {
  if (!has(name)) throw Error(fmt::format("{} is missing", where(name)));
  Handle set(checked(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), where(name) + " is not a dataset"),
             H5Dclose);
  Handle space(checked(H5Dget_space(set), "dataspace of " + where(name)), H5Sclose);
  Handle type(checked(H5Dget_type(set), "type of " + where(name)), H5Tclose);
  DatasetInfo out;
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) throw Error("HDF5 error: cannot read the shape of " + where(name));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  out.dims.assign(dims.begin(), dims.end());
  std::tie(out.type_class, out.type_size) = describe_type(type);
  Handle props(checked(H5Dget_create_plist(set), "properties of " + where(name)), H5Pclose);
  const int filters = H5Pget_nfilters(props);
  for (int k = 0; k < filters; ++k) {
    unsigned flags = 0;
    std::size_t count = 0;
    unsigned filter_config = 0;
    if (H5Pget_filter2(props, static_cast<unsigned>(k), &flags, &count, nullptr, 0, nullptr,
                       &filter_config) == H5Z_FILTER_DEFLATE)
      out.filter = "deflate";
  }
  return out;
}

template <class T>
std::vector<T> Group::read(const std::string& name, std::size_t rows, std::size_t columns) const {
  static_assert(kSupported<T>);
  const DatasetInfo stored = info(name);
  const std::vector<std::uint64_t> expected =
      columns == 1 ? std::vector<std::uint64_t>{rows} : std::vector<std::uint64_t>{rows, columns};
  if (stored.dims != expected || stored.type_class != type_class_of<T>() ||
      stored.type_size != sizeof(T))
    throw Error(
        fmt::format("{} has the wrong shape or type ({} of {}{} bytes, expected {} of "
                    "{}{} bytes)",
                    where(name), fmt::join(stored.dims, " x "), stored.type_class, stored.type_size,
                    fmt::join(expected, " x "), type_class_of<T>(), sizeof(T)));
  std::vector<T> data(rows * columns);
  Handle set(checked(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), "cannot open " + where(name)),
             H5Dclose);
  if (!data.empty())
    checked_status(H5Dread(set, memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                   "cannot read " + where(name));
  return data;
}

void Group::write_string(const std::string& name, const std::string& text) const {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  checked_status(H5Tset_size(type, text.size() + 1), "string type for " + where(name));
  Handle space(checked(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  Handle set(
      checked(H5Dcreate2(id_, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              "cannot create " + where(name)),
      H5Dclose);
  checked_status(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.c_str()),
                 "cannot write " + where(name));
}

std::string Group::read_string(const std::string& name) const {
  const DatasetInfo stored = info(name);
  if (stored.type_class != 's' || !stored.dims.empty() || stored.type_size == 0)
    throw Error(fmt::format("{} is not a string", where(name)));
  Handle set(checked(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), "cannot open " + where(name)),
             H5Dclose);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, stored.type_size);
  std::string buffer(stored.type_size, '\0');
  checked_status(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
                 "cannot read " + where(name));
  buffer.resize(std::min(buffer.size(), buffer.find('\0')));
  return buffer;
}

void Group::write_strings(const std::string& name, const std::vector<std::string>& items) const {
  std::size_t width = 1;
  for (const auto& s : items) width = std::max(width, s.size() + 1);
  std::vector<char> buffer(width * items.size(), '\0');
  for (std::size_t k = 0; k < items.size(); ++k)
    std::copy(items[k].begin(), items[k].end(), buffer.begin() + static_cast<long>(k * width));
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, width);
  const hsize_t dims[1] = {items.size()};
  Handle space(checked(H5Screate_simple(1, dims, nullptr), "dataspace"), H5Sclose);
  Handle set(
      checked(H5Dcreate2(id_, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              "cannot create " + where(name)),
      H5Dclose);
  if (!items.empty())
    checked_status(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
                   "cannot write " + where(name));
}

std::vector<std::string> Group::read_strings(const std::string& name) const {
  const DatasetInfo stored = info(name);
  if (stored.type_class != 's' || stored.dims.size() != 1 || stored.type_size == 0)
    throw Error(fmt::format("{} is not a list of strings", where(name)));
  const std::size_t width = stored.type_size, count = stored.dims[0];
  Handle set(checked(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), "cannot open " + where(name)),
             H5Dclose);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, width);
  std::vector<char> buffer(width * count, '\0');
  if (count > 0)
    checked_status(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
                   "cannot read " + where(name));
  std::vector<std::string> items;
  for (std::size_t k = 0; k < count; ++k) {
    const char* begin = buffer.data() + k * width;
    items.emplace_back(begin, std::find(begin, begin + width, '\0'));
  }
  return items;
}

template <class T>
void Group::set_attribute(const std::string& name, T value) const {
  static_assert(kSupported<T>);
  if (has_attribute(name))
    checked_status(H5Adelete(id_, name.c_str()), "cannot replace attribute " + where(name));
  Handle space(checked(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  Handle attr(
      checked(H5Acreate2(id_, name.c_str(), memory_type<T>(), space, H5P_DEFAULT, H5P_DEFAULT),
              "cannot create attribute " + where(name)),
      H5Aclose);
  checked_status(H5Awrite(attr, memory_type<T>(), &value), "cannot write attribute " + where(name));
}

template <class T>
T Group::attribute(const std::string& name) const {
  static_assert(kSupported<T>);
  if (!has_attribute(name)) throw Error(fmt::format("attribute {} is missing", where(name)));
  Handle attr(checked(H5Aopen(id_, name.c_str(), H5P_DEFAULT), "cannot open attribute " + name),
              H5Aclose);
  Handle type(checked(H5Aget_type(attr), "type of attribute " + where(name)), H5Tclose);
  Handle space(checked(H5Aget_space(attr), "dataspace of attribute " + where(name)), H5Sclose);
  const auto [type_class, size] = describe_type(type);
  if (type_class != type_class_of<T>() || size != sizeof(T) ||
      H5Sget_simple_extent_type(space) != H5S_SCALAR)
    throw Error(fmt::format("attribute {} has the wrong type", where(name)));
  T value{};
  checked_status(H5Aread(attr, memory_type<T>(), &value), "cannot read attribute " + where(name));
  return value;
}

bool Group::has_attribute(const std::string& name) const {
  return H5Aexists(id_, name.c_str()) > 0;
}

#define MPSOLID_H5_INSTANTIATE(T)                                                                \
  template void Group::write<T>(const std::string&, const std::vector<T>&, std::size_t, int)     \
      const;                                                                                     \
  template std::vector<T> Group::read<T>(const std::string&, std::size_t, std::size_t) const;    \
  template std::uint64_t Group::reserve<T>(const std::string&, std::size_t, std::size_t) const;  \
  template void Group::create<T>(const std::string&, std::size_t, std::size_t, int) const;       \
  template void Group::write_rows<T>(const std::string&, std::size_t, const std::vector<T>&,     \
                                     std::size_t) const;                                         \
  template std::optional<std::uint64_t> Group::placed_offset<T>(const std::string&, std::size_t, \
                                                                std::size_t) const;              \
  template void Group::set_attribute<T>(const std::string&, T) const;                            \
  template T Group::attribute<T>(const std::string&) const;
MPSOLID_H5_INSTANTIATE(double)
MPSOLID_H5_INSTANTIATE(std::int8_t)
MPSOLID_H5_INSTANTIATE(std::int32_t)
MPSOLID_H5_INSTANTIATE(std::int64_t)
MPSOLID_H5_INSTANTIATE(std::uint64_t)
#undef MPSOLID_H5_INSTANTIATE

File::File(File&& other) noexcept : Group(std::move(other)), file_(other.file_) {
  other.file_ = -1;
}

File& File::operator=(File&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) H5Gclose(id_);
    id_ = -1;
    if (file_ >= 0) H5Fclose(file_);
    Group::operator=(std::move(other));
    file_ = other.file_;
    other.file_ = -1;
  }
  return *this;
}

File::~File() {
  if (id_ >= 0) H5Gclose(id_);
  id_ = -1;
  if (file_ >= 0) H5Fclose(file_);
}

File File::create(const std::filesystem::path& path) {
  silence_hdf5();
  const hid_t file = checked(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                             "cannot create " + path.string());
  const hid_t root = H5Gopen2(file, "/", H5P_DEFAULT);
  if (root < 0) {
    H5Fclose(file);
    throw Error("HDF5 error: cannot open the root group of " + path.string());
  }
  return File(root, file, path.string() + ":/");
}

File File::open(const std::filesystem::path& path, bool writable) {
  silence_hdf5();
  if (!is_hdf5_file(path)) throw Error(fmt::format("{} is not an HDF5 file", path.string()));
  const hid_t file =
      checked(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT),
              fmt::format("cannot open {} (damaged or truncated?)", path.string()));
  const hid_t root = H5Gopen2(file, "/", H5P_DEFAULT);
  if (root < 0) {
    H5Fclose(file);
    throw Error("HDF5 error: cannot open the root group of " + path.string());
  }
  return File(root, file, path.string() + ":/");
}

void File::flush() const {
  checked_status(H5Fflush(file_, H5F_SCOPE_GLOBAL), "cannot flush " + path_);
}

std::uintmax_t File::size() const {
  hsize_t size = 0;
  checked_status(H5Fget_filesize(file_, &size), "cannot get the size of " + path_);
  return size;
}

void File::close() {
  if (id_ >= 0) H5Gclose(id_);
  id_ = -1;
  const hid_t file = file_;
  file_ = -1;
  if (file >= 0) checked_status(H5Fclose(file), "cannot close " + path_);
}

bool is_hdf5_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char signature[8] = {};
  return in.read(signature, 8) && std::equal(signature, signature + 8, "\x89HDF\r\n\x1a\n");
}

}  // namespace mpsolid::h5
