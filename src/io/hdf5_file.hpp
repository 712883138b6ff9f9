#pragma once
// A thin layer over the HDF5 C API for frames.h5 and checkpoint.h5: files and
// groups that close themselves, numeric datasets (1-D, or rows x columns),
// strings and scalar attributes. The only file that includes hdf5.h; every
// failure is an h5::Error naming the object.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpsolid::h5 {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The element types a dataset or attribute may hold (explicitly instantiated
// for double, std::int8_t, std::int32_t, std::int64_t, std::uint64_t).
template <class T>
inline constexpr bool kSupported = false;
template <>
inline constexpr bool kSupported<double> = true;
template <>
inline constexpr bool kSupported<std::int8_t> = true;
template <>
inline constexpr bool kSupported<std::int32_t> = true;
template <>
inline constexpr bool kSupported<std::int64_t> = true;
template <>
inline constexpr bool kSupported<std::uint64_t> = true;

// Shape and element type of a stored dataset.
struct DatasetInfo {
  std::vector<std::uint64_t> dims;
  char type_class = '?';  // 'f' float, 'i' signed integer, 'u' unsigned, 's' string, '?' other
  std::size_t type_size = 0;
  std::string filter;  // "deflate" when compressed, else ""
};

// The rows of a compressed dataset's chunks (the last one may be shorter).
constexpr std::size_t kChunkRows = 65536;

// An open group (or, as File, the root group of an open file).
class Group {
 public:
  Group() = default;
  Group(Group&& other) noexcept;
  Group& operator=(Group&& other) noexcept;
  Group(const Group&) = delete;
  Group& operator=(const Group&) = delete;
  virtual ~Group();

  bool is_open() const { return id_ >= 0; }
  Group create_group(const std::string& name) const;
  Group open_group(const std::string& name) const;
  bool has(const std::string& name) const;
  void remove(const std::string& name) const;
  // Names of the links in this group, in name order.
  std::vector<std::string> children() const;

  // A dataset of rows x columns (1-D when columns == 1); deflate level 0 (off)
  // to 9, with byte shuffling.
  template <class T>
  void write(const std::string& name, const std::vector<T>& data, std::size_t columns = 1,
             int deflate = 0) const;
  // A dataset of rows x columns stored as write() stores it (deflate level
  // `deflate`, chunks of kChunkRows rows), its rows written later
  // (write_rows), chunk by chunk where compressed.
  template <class T>
  void create(const std::string& name, std::size_t rows, std::size_t columns = 1,
              int deflate = 0) const;
  // Rows first, first + 1, ... of a dataset of `columns` columns: data.size()
  // / columns of them.
  template <class T>
  void write_rows(const std::string& name, std::size_t first, const std::vector<T>& data,
                  std::size_t columns = 1) const;
  // A contiguous dataset of rows x columns (1-D when columns == 1), its
  // space allocated now and never filled, for rows written in place by other
  // processes: returns the file offset of its first byte (row k at offset +
  // k * columns * sizeof(T), native numbers as in memory); 0 when empty.
  template <class T>
  std::uint64_t reserve(const std::string& name, std::size_t rows, std::size_t columns = 1) const;
  // Where a dataset of rows x columns of T stored as reserve() stores it
  // (contiguous, unfiltered, native numbers, its space allocated) starts in
  // the file, for rows read in place by other processes; nullopt when it is
  // stored otherwise or has another shape (0 when empty).
  template <class T>
  std::optional<std::uint64_t> placed_offset(const std::string& name, std::size_t rows,
                                             std::size_t columns = 1) const;
  // Reads a dataset that must be rows x columns of T (1-D when columns == 1).
  template <class T>
  std::vector<T> read(const std::string& name, std::size_t rows, std::size_t columns = 1) const;
  DatasetInfo info(const std::string& name) const;

  void write_string(const std::string& name, const std::string& text) const;
  std::string read_string(const std::string& name) const;
  void write_strings(const std::string& name, const std::vector<std::string>& items) const;
  std::vector<std::string> read_strings(const std::string& name) const;

  template <class T>
  void set_attribute(const std::string& name, T value) const;
  template <class T>
  T attribute(const std::string& name) const;
  bool has_attribute(const std::string& name) const;

 protected:
  Group(std::int64_t id, std::string path) : id_(id), path_(std::move(path)) {}
  std::string where(const std::string& name) const;
  std::int64_t id_ = -1;
  std::string path_;  // "file:/group", for messages
};

class File : public Group {
 public:
  File() = default;
  File(File&& other) noexcept;
  File& operator=(File&& other) noexcept;
  ~File() override;

  static File create(const std::filesystem::path& path);  // replaces any file there
  static File open(const std::filesystem::path& path, bool writable);
  void flush() const;
  std::uintmax_t size() const;
  void close();  // the root group and the file (also done by the destructor)

 private:
  File(std::int64_t group, std::int64_t file, std::string path)
      : Group(group, std::move(path)), file_(file) {}
  std::int64_t file_ = -1;
};

// True if `path` starts with the HDF5 signature.
bool is_hdf5_file(const std::filesystem::path& path);

}  // namespace mpsolid::h5
