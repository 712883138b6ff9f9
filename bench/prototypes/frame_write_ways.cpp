// Three ways for R MPI ranks to write one particle frame into one HDF5 file,
// timed from the start of the write to the file closed and fsynced (the
// fsync is inside the timing: without it the figure is the page cache's),
// on rank 0 with MPI_Barrier before, after the write and close ("cache":
// the data handed to the page cache) and after the fsync ("sec": total).
// The frame: N particles in group /frames/000000, datasets id int32, kind
// int8, body int32, position f64 Nx2, velocity f64 Nx2, rotation,
// angular_velocity, volumetric_strain, pressure f64, surface int8, normal
// f64 Nx2 (90 bytes a particle). Rank r owns rows [r*N/R, (r+1)*N/R) and
// fills them with values that are functions of the row index (fill()).
// Ways (first argument):
//   gather  every rank MPI_Gatherv's its rows of each dataset to rank 0, which
//           H5Dwrite's the whole dataset with a serial (sec2) file;
//   pcoll   parallel HDF5 (H5Pset_fapl_mpio), each rank writes its hyperslab,
//           H5FD_MPIO_COLLECTIVE transfer; pindep: the same, INDEPENDENT
//           (only in a build against a parallel HDF5, H5_HAVE_PARALLEL);
//   direct  rank 0 creates the file (contiguous, alloc time early, fill
//           time never), reads each dataset's H5Dget_offset and closes it;
//           the offsets are broadcast and every rank pwrite()s its rows at
//           offset + first_row * row_bytes, closes; after the barrier every
//           rank opens the file again, fsyncs it and closes it.
// All ways use the same dataset creation properties (contiguous, early
// allocation, fill never). For gather and pcoll/pindep the fsync is done by
// rank 0 on the closed file (one node: it flushes every rank's pages).
// Rank 0 then (outside the timing) reads every dataset back with the HDF5
// library and compares it with fill() bit for bit. Each rank's peak resident
// memory (getrusage ru_maxrss) is printed before the write (after filling its
// own rows) and after it; run each way in its own process for the peak.
// Not part of the build. Serial HDF5 (gather, direct):
//   mpicxx -O2 -std=c++17 -I/usr/include/hdf5/serial
//     bench/prototypes/frame_write_ways.cpp -o /tmp/fww_serial -lhdf5_serial
// Parallel HDF5 (all four), from the Debian .debs unpacked, not installed:
//   cd /tmp && apt-get download libhdf5-openmpi-dev libhdf5-openmpi-103-1
//     libhdf5-openmpi-hl-100 && for f in libhdf5-openmpi*.deb; do dpkg -x $f
//     /tmp/phdf5; done
//   mpicxx -O2 -std=c++17 -I/tmp/phdf5/usr/include/hdf5/openmpi
//     bench/prototypes/frame_write_ways.cpp -o /tmp/fww_par
//     -L/tmp/phdf5/usr/lib/x86_64-linux-gnu/hdf5/openmpi -lhdf5
// Run (way N directory [keep]; keep leaves the file for h5dump), e.g. from
// /tmp after mkdir -p /tmp/frames:
//   mpirun --allow-run-as-root --oversubscribe -np 3 /tmp/fww_serial direct 10000000 /tmp/frames
//   LD_LIBRARY_PATH=/tmp/phdf5/usr/lib/x86_64-linux-gnu mpirun --allow-run-as-root
//     --oversubscribe -x LD_LIBRARY_PATH -np 3 /tmp/fww_par pcoll 10000000 /tmp/frames
#include <hdf5.h>
#include <mpi.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Field {
  const char* name;
  char type;  // 'i' int32, 'b' int8, 'd' float64
  int cols;
};
const Field kFields[] = {{"id", 'i', 1},
                         {"kind", 'b', 1},
                         {"body", 'i', 1},
                         {"position", 'd', 2},
                         {"velocity", 'd', 2},
                         {"rotation", 'd', 1},
                         {"angular_velocity", 'd', 1},
                         {"volumetric_strain", 'd', 1},
                         {"pressure", 'd', 1},
                         {"surface", 'b', 1},
                         {"normal", 'd', 2}};
constexpr int kNF = sizeof(kFields) / sizeof(kFields[0]);

int elem_bytes(const Field& f) {
  return f.type == 'i' ? 4 : f.type == 'b' ? 1 : 8;
}
std::size_t row_bytes(const Field& f) {
  return std::size_t(elem_bytes(f)) * f.cols;
}
hid_t mem_type(const Field& f) {
  return f.type == 'i' ? H5T_NATIVE_INT32 : f.type == 'b' ? H5T_NATIVE_INT8 : H5T_NATIVE_DOUBLE;
}
hid_t file_type(const Field& f) {
  return f.type == 'i' ? H5T_STD_I32LE : f.type == 'b' ? H5T_STD_I8LE : H5T_IEEE_F64LE;
}

[[noreturn]] void die(const char* what) {
  std::fprintf(stderr, "error: %s (errno %d: %s)\n", what, errno, std::strerror(errno));
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}
template <class T>
T chk(T v, const char* what) {
  if (v < 0) die(what);
  return v;
}

// Deterministic contents: a function of (field, row, column); doubles exact.
void fill(int fi, int64_t r0, int64_t rows, char* out) {
  const Field& f = kFields[fi];
  for (int64_t r = r0; r < r0 + rows; ++r)
    for (int c = 0; c < f.cols; ++c) {
      const int64_t s = r * 3 + c + fi * 7;
      if (f.type == 'i') {
        int32_t v = int32_t(s % 2000000000);
        std::memcpy(out, &v, 4);
      } else if (f.type == 'b') {
        int8_t v = int8_t(s % 101);
        std::memcpy(out, &v, 1);
      } else {
        double v = double(s) * 0.5 + 0.25;
        std::memcpy(out, &v, 8);
      }
      out += elem_bytes(f);
    }
}

double peak_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // KiB on Linux
}

void fsync_path(const std::string& path) {
  int fd = open(path.c_str(), O_RDWR);
  if (fd < 0) die("open for fsync");
  if (fsync(fd) != 0) die("fsync");
  close(fd);
}

// Creates /frames/000000 and its datasets (collective when fapl is mpio).
std::vector<hid_t> create_frame(hid_t file, int64_t n) {
  hid_t g1 = chk(H5Gcreate2(file, "/frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "group");
  hid_t g = chk(H5Gcreate2(file, "/frames/000000", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "group");
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  chk(H5Pset_layout(dcpl, H5D_CONTIGUOUS), "layout");
  chk(H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_EARLY), "alloc time");
  chk(H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER), "fill time");
  std::vector<hid_t> ds;
  for (const Field& f : kFields) {
    hsize_t dims[2] = {hsize_t(n), hsize_t(f.cols)};
    hid_t sp = H5Screate_simple(f.cols == 1 ? 1 : 2, dims, nullptr);
    ds.push_back(chk(H5Dcreate2(g, f.name, file_type(f), sp, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                     "dataset create"));
    H5Sclose(sp);
  }
  H5Pclose(dcpl);
  H5Gclose(g);
  H5Gclose(g1);
  return ds;
}

void close_all(std::vector<hid_t>& ds, hid_t file) {
  for (hid_t d : ds) H5Dclose(d);
  chk(H5Fclose(file), "file close");
}

struct Part {
  int rank, size;
  int64_t n, r0, rows;
  std::vector<std::vector<char>> local;  // this rank's rows of each field
};

void write_gather(const std::string& path, const Part& p) {
  hid_t file = -1;
  std::vector<hid_t> ds;
  std::vector<char> full;
  if (p.rank == 0) {
    file = chk(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create");
    ds = create_frame(file, p.n);
    full.resize(std::size_t(p.n) * 16);  // the widest field
  }
  std::vector<int> counts(p.size), displs(p.size);
  for (int fi = 0; fi < kNF; ++fi) {
    const std::size_t rb = row_bytes(kFields[fi]);
    for (int r = 0; r < p.size; ++r) {
      const int64_t a = r * p.n / p.size, b = (r + 1) * p.n / p.size;
      if ((b - a) * rb > INT32_MAX || b * rb > INT32_MAX) die("too large for int counts");
      counts[r] = int((b - a) * rb);
      displs[r] = int(a * rb);
    }
    MPI_Gatherv(p.local[fi].data(), counts[p.rank], MPI_BYTE, full.data(), counts.data(),
                displs.data(), MPI_BYTE, 0, MPI_COMM_WORLD);
    if (p.rank == 0)
      chk(H5Dwrite(ds[fi], mem_type(kFields[fi]), H5S_ALL, H5S_ALL, H5P_DEFAULT, full.data()),
          "write");
  }
  if (p.rank == 0) {
    close_all(ds, file);
  }
}

#ifdef H5_HAVE_PARALLEL
void write_parallel(const std::string& path, const Part& p, bool collective) {
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  chk(H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL), "fapl mpio");
  hid_t file = chk(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "create");
  H5Pclose(fapl);
  std::vector<hid_t> ds = create_frame(file, p.n);
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  chk(H5Pset_dxpl_mpio(dxpl, collective ? H5FD_MPIO_COLLECTIVE : H5FD_MPIO_INDEPENDENT), "dxpl");
  for (int fi = 0; fi < kNF; ++fi) {
    const Field& f = kFields[fi];
    hsize_t start[2] = {hsize_t(p.r0), 0}, count[2] = {hsize_t(p.rows), hsize_t(f.cols)};
    hid_t fs = H5Dget_space(ds[fi]);
    hid_t ms = H5Screate_simple(f.cols == 1 ? 1 : 2, count, nullptr);
    if (p.rows > 0) {
      chk(H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, nullptr, count, nullptr), "hyperslab");
    } else {
      H5Sselect_none(fs);
      H5Sselect_none(ms);
    }
    chk(H5Dwrite(ds[fi], mem_type(f), ms, fs, dxpl, p.local[fi].data()), "write");
    H5Sclose(ms);
    H5Sclose(fs);
  }
  H5Pclose(dxpl);
  close_all(ds, file);
}
#endif

void write_direct(const std::string& path, const Part& p) {
  std::vector<uint64_t> off(kNF);
  if (p.rank == 0) {
    hid_t file = chk(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create");
    std::vector<hid_t> ds = create_frame(file, p.n);
    for (int fi = 0; fi < kNF; ++fi) {
      haddr_t a = H5Dget_offset(ds[fi]);
      if (a == HADDR_UNDEF) die("H5Dget_offset returned HADDR_UNDEF");
      off[fi] = a;
    }
    close_all(ds, file);
  }
  MPI_Bcast(off.data(), kNF, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  int fd = open(path.c_str(), O_WRONLY);
  if (fd < 0) die("open");
  for (int fi = 0; fi < kNF; ++fi) {
    const char* buf = p.local[fi].data();
    std::size_t left = p.local[fi].size();
    off_t at = off_t(off[fi] + uint64_t(p.r0) * row_bytes(kFields[fi]));
    while (left > 0) {
      ssize_t w = pwrite(fd, buf, left, at);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) die("pwrite");
      buf += w, at += w, left -= std::size_t(w);
    }
  }
  close(fd);
}

// Rank 0: the HDF5 library reads every dataset back; compare with fill().
bool verify(const std::string& path, int64_t n) {
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return false;
  bool ok = true;
  std::vector<char> got, want;
  for (int fi = 0; fi < kNF && ok; ++fi) {
    const Field& f = kFields[fi];
    std::string name = std::string("/frames/000000/") + f.name;
    hid_t d = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
    hid_t sp = H5Dget_space(d);
    hsize_t dims[2] = {0, 0};
    int nd = H5Sget_simple_extent_dims(sp, dims, nullptr);
    ok = d >= 0 && nd == (f.cols == 1 ? 1 : 2) && dims[0] == hsize_t(n) &&
         (nd == 1 || dims[1] == hsize_t(f.cols));
    got.assign(std::size_t(n) * row_bytes(f), 0);
    want.resize(got.size());
    ok = ok && H5Dread(d, mem_type(f), H5S_ALL, H5S_ALL, H5P_DEFAULT, got.data()) >= 0;
    fill(fi, 0, n, want.data());
    if (ok && std::memcmp(got.data(), want.data(), got.size()) != 0) ok = false;
    if (!ok) std::fprintf(stderr, "verify: dataset %s differs\n", f.name);
    H5Sclose(sp);
    H5Dclose(d);
  }
  H5Fclose(file);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  Part p;
  MPI_Comm_rank(MPI_COMM_WORLD, &p.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &p.size);
  if (argc < 4) {
    if (p.rank == 0)
      std::fprintf(stderr, "usage: %s gather|pcoll|pindep|direct N directory [keep]\n", argv[0]);
    MPI_Finalize();
    return 2;
  }
  const std::string way = argv[1], path = std::string(argv[3]) + "/frame_" + way + ".h5";
  const bool keep = argc > 4 && std::string(argv[4]) == "keep";
  p.n = std::atoll(argv[2]);
  p.r0 = p.rank * p.n / p.size;
  p.rows = (p.rank + 1) * p.n / p.size - p.r0;
  for (int fi = 0; fi < kNF; ++fi) {
    p.local.emplace_back(std::size_t(p.rows) * row_bytes(kFields[fi]));
    fill(fi, p.r0, p.rows, p.local[fi].data());
  }
  const double before = peak_mib();

  MPI_Barrier(MPI_COMM_WORLD);
  const double t0 = MPI_Wtime();
  if (way == "gather")
    write_gather(path, p);
  else if (way == "direct")
    write_direct(path, p);
#ifdef H5_HAVE_PARALLEL
  else if (way == "pcoll" || way == "pindep")
    write_parallel(path, p, way == "pcoll");
#endif
  else
    die(("unknown way (or needs parallel HDF5): " + way).c_str());
  MPI_Barrier(MPI_COMM_WORLD);
  const double cache = MPI_Wtime() - t0;
  if (way == "direct" || p.rank == 0) fsync_path(path);  // one node: flushes all ranks' pages
  MPI_Barrier(MPI_COMM_WORLD);
  const double sec = MPI_Wtime() - t0;

  double mine[2] = {before, peak_mib()};
  std::vector<double> all(2 * p.size);
  MPI_Gather(mine, 2, MPI_DOUBLE, all.data(), 2, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (p.rank == 0) {
    unsigned maj, min, rel;
    H5get_libversion(&maj, &min, &rel);
#ifdef H5_HAVE_PARALLEL
    const char* lib = "parallel";
#else
    const char* lib = "serial";
#endif
    const bool ok = verify(path, p.n);
    const double bytes = double(p.n) * 90;
    std::printf("RESULT way=%s lib=%s-%u.%u.%u R=%d N=%lld sec=%.3f GBps=%.3f cache=%.3f",
                way.c_str(), lib, maj, min, rel, p.size, (long long)p.n, sec, bytes / sec / 1e9,
                cache);
    for (int r = 0; r < p.size; ++r)
      std::printf(" rss%d_MiB=%.0f/%.0f", r, all[2 * r], all[2 * r + 1]);
    std::printf(" verify=%s\n", ok ? "ok" : "FAILED");
    if (!keep) unlink(path.c_str());
  }
  MPI_Finalize();
  return 0;
}
