// Writing and reading Newton systems in PETSc's binary format, see tangent_dump.hpp. The format
// is written here directly (class id, sizes, row lengths, columns, values; 32-bit big-endian
// integers, big-endian doubles) so that the dump needs no PETSc at run time.
#include "solver/tangent_dump.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace cc {

namespace {

constexpr std::int32_t kMatrixClassId = 1211216;  // PETSc's MAT_FILE_CLASSID
constexpr std::int32_t kVectorClassId = 1211214;  // VEC_FILE_CLASSID

template <class T>
T bigEndian(T value) {
  if constexpr (std::endian::native == std::endian::big) return value;
  auto bytes = std::bit_cast<std::array<unsigned char, sizeof(T)>>(value);
  std::reverse(bytes.begin(), bytes.end());
  return std::bit_cast<T>(bytes);
}

class BinaryWriter {
 public:
  explicit BinaryWriter(const std::string& path) : path_(path), out_(path, std::ios::binary) {
    if (!out_) throw std::runtime_error("cannot write " + path);
  }
  template <class T>
  void put(T value) {
    value = bigEndian(value);
    out_.write(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void finish() {
    out_.close();
    if (!out_) throw std::runtime_error("error writing " + path_);
  }

 private:
  std::string path_;
  std::ofstream out_;
};

class BinaryReader {
 public:
  explicit BinaryReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw std::runtime_error("cannot read " + path);
  }
  template <class T>
  T get() {
    T value{};
    in_.read(reinterpret_cast<char*>(&value), sizeof(T));
    if (!in_) throw std::runtime_error("truncated file " + path_);
    return bigEndian(value);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
};

void writeVector(BinaryWriter& out, const Eigen::VectorXd& vector) {
  out.put(kVectorClassId);
  out.put(static_cast<std::int32_t>(vector.size()));
  for (Eigen::Index i = 0; i < vector.size(); ++i) out.put(vector[i]);
}

Eigen::VectorXd readVector(BinaryReader& in) {
  if (in.get<std::int32_t>() != kVectorClassId) {
    throw std::runtime_error(in.path() + ": not a PETSc binary vector");
  }
  Eigen::VectorXd vector(in.get<std::int32_t>());
  for (Eigen::Index i = 0; i < vector.size(); ++i) vector[i] = in.get<double>();
  return vector;
}

// Rows are equations: CSR of K = CSC of K^T, so write the transpose's columns.
void writeMatrix(const std::string& path, const SparseMatrix& matrix) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor, int> rows = matrix;
  BinaryWriter out(path);
  out.put(kMatrixClassId);
  out.put(static_cast<std::int32_t>(rows.rows()));
  out.put(static_cast<std::int32_t>(rows.cols()));
  out.put(static_cast<std::int32_t>(rows.nonZeros()));
  for (Eigen::Index r = 0; r < rows.rows(); ++r) {
    out.put(static_cast<std::int32_t>(rows.outerIndexPtr()[r + 1] - rows.outerIndexPtr()[r]));
  }
  for (Eigen::Index k = 0; k < rows.nonZeros(); ++k) out.put(rows.innerIndexPtr()[k]);
  for (Eigen::Index k = 0; k < rows.nonZeros(); ++k) out.put(rows.valuePtr()[k]);
  out.finish();
}

SparseMatrix readMatrix(const std::string& path) {
  BinaryReader in(path);
  if (in.get<std::int32_t>() != kMatrixClassId) {
    throw std::runtime_error(path + ": not a PETSc binary matrix");
  }
  const int rows = in.get<std::int32_t>(), cols = in.get<std::int32_t>();
  const int nonZeros = in.get<std::int32_t>();
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> matrix(rows, cols);
  matrix.resizeNonZeros(nonZeros);
  matrix.outerIndexPtr()[0] = 0;
  for (int r = 0; r < rows; ++r) {
    matrix.outerIndexPtr()[r + 1] = matrix.outerIndexPtr()[r] + in.get<std::int32_t>();
  }
  for (int k = 0; k < nonZeros; ++k) matrix.innerIndexPtr()[k] = in.get<std::int32_t>();
  for (int k = 0; k < nonZeros; ++k) matrix.valuePtr()[k] = in.get<double>();
  return SparseMatrix(matrix);
}

// Translations and rotations about the centroid of the nodes that carry free equations.
Eigen::MatrixXd rigidBodyModes(const std::vector<int>& freeDofs,
                               const Eigen::Matrix3Xd& coordinates) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int dof : freeDofs) centroid += coordinates.col(dof / 3);
  if (!freeDofs.empty()) centroid /= static_cast<double>(freeDofs.size());
  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(freeDofs.size()), 6);
  for (std::size_t e = 0; e < freeDofs.size(); ++e) {
    const int component = freeDofs[e] % 3;
    const Eigen::Vector3d x = coordinates.col(freeDofs[e] / 3) - centroid;
    modes(static_cast<Eigen::Index>(e), component) = 1;
    for (int axis = 0; axis < 3; ++axis) {
      // component `component` of (e_axis x x)
      const Eigen::Vector3d rotation = Eigen::Vector3d(Eigen::Vector3d::Unit(axis)).cross(x);
      modes(static_cast<Eigen::Index>(e), 3 + axis) = rotation[component];
    }
  }
  return modes;
}

}  // namespace

void writeTangentDump(const std::string& directory, const SystemMatrices& system,
                      const Eigen::VectorXd& rhs, const DofMap& dofs,
                      const Eigen::Matrix3Xd& coordinates) {
  std::filesystem::create_directories(directory);
  const std::filesystem::path dir(directory);
  writeMatrix((dir / "matrix.petsc").string(), system.free);
  {
    BinaryWriter out((dir / "rhs.petsc").string());
    writeVector(out, rhs);
    out.finish();
  }
  {
    const Eigen::MatrixXd modes = rigidBodyModes(dofs.freeDofs(), coordinates);
    BinaryWriter out((dir / "nullspace.petsc").string());
    for (int k = 0; k < 6; ++k) writeVector(out, modes.col(k));
    out.finish();
  }
  {
    Eigen::VectorXd freeDofs(static_cast<Eigen::Index>(dofs.freeDofs().size()));
    for (std::size_t e = 0; e < dofs.freeDofs().size(); ++e) {
      freeDofs[static_cast<Eigen::Index>(e)] = dofs.freeDofs()[e];
    }
    BinaryWriter out((dir / "free_dofs.petsc").string());
    writeVector(out, freeDofs);
    out.finish();
  }
  {
    BinaryWriter out((dir / "coordinates.petsc").string());
    writeVector(out, Eigen::Map<const Eigen::VectorXd>(coordinates.data(), coordinates.size()));
    out.finish();
  }
  std::ofstream info(dir / "info.txt");
  info << fmt::format("equations {}\nnonzeros {}\nsymmetric {}\nnodes {}\n", system.free.rows(),
                      system.free.nonZeros(), system.symmetric ? 1 : 0, coordinates.cols());
  if (!info) throw std::runtime_error("cannot write " + (dir / "info.txt").string());
}

TangentDump readTangentDump(const std::string& directory) {
  const std::filesystem::path dir(directory);
  TangentDump dump;
  dump.matrix = readMatrix((dir / "matrix.petsc").string());
  {
    BinaryReader in((dir / "rhs.petsc").string());
    dump.rhs = readVector(in);
  }
  {
    BinaryReader in((dir / "nullspace.petsc").string());
    dump.nullspace.resize(dump.matrix.rows(), 6);
    for (int k = 0; k < 6; ++k) dump.nullspace.col(k) = readVector(in);
  }
  {
    BinaryReader in((dir / "free_dofs.petsc").string());
    const Eigen::VectorXd freeDofs = readVector(in);
    dump.layout.freeDofs.assign(freeDofs.data(), freeDofs.data() + freeDofs.size());
  }
  {
    BinaryReader in((dir / "coordinates.petsc").string());
    const Eigen::VectorXd coordinates = readVector(in);
    dump.layout.coordinates =
        Eigen::Map<const Eigen::Matrix3Xd>(coordinates.data(), 3, coordinates.size() / 3);
  }
  std::ifstream info(dir / "info.txt");
  std::string key;
  long value = 0;
  while (info >> key >> value) {
    if (key == "symmetric") dump.symmetric = value != 0;
  }
  if (dump.rhs.size() != dump.matrix.rows() ||
      static_cast<Eigen::Index>(dump.layout.freeDofs.size()) != dump.matrix.rows()) {
    throw std::runtime_error(directory + ": matrix, rhs and free_dofs sizes differ");
  }
  return dump;
}

}  // namespace cc
