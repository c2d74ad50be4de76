// Step and link naming and the compound row types of the results file layout.
#include "output/results_layout.hpp"

#include <cstddef>
#include <cstdio>
#include <cstring>

namespace cc::layout {

std::string stepGroupName(int step) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d", step);
  return name;
}

std::string stepGroupPath(int step) {
  return std::string(kStepsGroup) + "/" + stepGroupName(step);
}

std::string linkName(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return "_" + name;
  std::string link = name;
  for (char& c : link)
    if (c == '/') c = '_';
  return link;
}

h5::Type convergenceRowType() {
  h5::Type type(H5Tcreate(H5T_COMPOUND, sizeof(ConvergenceRow)));
  const hid_t id = type.get();
  H5Tinsert(id, "step", offsetof(ConvergenceRow, step), H5T_NATIVE_INT);
  H5Tinsert(id, "attempt", offsetof(ConvergenceRow, attempt), H5T_NATIVE_INT);
  H5Tinsert(id, "iteration", offsetof(ConvergenceRow, iteration), H5T_NATIVE_INT);
  H5Tinsert(id, "time", offsetof(ConvergenceRow, time), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "residual", offsetof(ConvergenceRow, residual), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "relative_residual", offsetof(ConvergenceRow, relativeResidual), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "energy", offsetof(ConvergenceRow, energy), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "relative_energy", offsetof(ConvergenceRow, relativeEnergy), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "wall_seconds", offsetof(ConvergenceRow, wallSeconds), H5T_NATIVE_DOUBLE);
  return type;
}

h5::Type cutbackRowType() {
  h5::Type type(H5Tcreate(H5T_COMPOUND, sizeof(CutbackRow)));
  const hid_t id = type.get();
  const h5::Type text(H5Tcopy(H5T_C_S1));
  H5Tset_size(text.get(), kReasonBytes);
  H5Tset_strpad(text.get(), H5T_STR_NULLTERM);
  H5Tset_cset(text.get(), H5T_CSET_UTF8);
  H5Tinsert(id, "step", offsetof(CutbackRow, step), H5T_NATIVE_INT);
  H5Tinsert(id, "time", offsetof(CutbackRow, time), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "new_dt", offsetof(CutbackRow, newDt), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "reason", offsetof(CutbackRow, reason), text.get());
  return type;
}

h5::Type cutbackRowTypeV1() {
  h5::Type type(H5Tcreate(H5T_COMPOUND, sizeof(CutbackRowV1)));
  const hid_t id = type.get();
  const h5::Type text = h5::variableString();
  H5Tinsert(id, "step", offsetof(CutbackRowV1, step), H5T_NATIVE_INT);
  H5Tinsert(id, "time", offsetof(CutbackRowV1, time), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "new_dt", offsetof(CutbackRowV1, newDt), H5T_NATIVE_DOUBLE);
  H5Tinsert(id, "reason", offsetof(CutbackRowV1, reason), text.get());
  return type;
}

CutbackRow cutbackRow(int step, double time, double newDt, const std::string& reason) {
  CutbackRow row{step, time, newDt, {}};
  std::size_t length = reason.size();
  const char* ellipsis = "";
  if (length >= kReasonBytes) {
    length = kReasonBytes - 4;  // room for "..." and the terminator
    // Back up to the first byte of a UTF-8 character (continuation bytes are 10xxxxxx).
    while (length > 0 && (static_cast<unsigned char>(reason[length]) & 0xC0) == 0x80) --length;
    ellipsis = "...";
  }
  std::memcpy(row.reason, reason.data(), length);
  std::memcpy(row.reason + length, ellipsis, std::strlen(ellipsis) + 1);
  return row;
}

}  // namespace cc::layout
