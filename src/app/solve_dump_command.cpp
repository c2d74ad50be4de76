// `covcontact solve-dump DIR --solver X`: one linear solve of a dumped Newton system (run
// --dump-tangent) with one solver, timed by phase; prints one JSON line that
// scripts/solver_survey.py tabulates (it measures the process's peak memory itself).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <iostream>

#include "app/commands.hpp"
#include "common/errors.hpp"
#include "deck/spec_choices.hpp"
#include "fem/assembler.hpp"
#include "solver/tangent_dump.hpp"
#include "solver/tangent_solver.hpp"

namespace cc::app {

namespace {

std::optional<LinearSolverSpec::Method> methodNamed(const std::string& name) {
  for (const auto& [spelling, method] : deck::linearSolverMethods()) {
    if (name == spelling) return method;
  }
  return std::nullopt;
}

}  // namespace

int solveDumpCommand(const SolveDumpOptions& options) {
  const auto method = methodNamed(options.solver);
  if (!method) {
    std::cerr << "covcontact solve-dump: unknown --solver '" << options.solver << "'\n";
    return kExitUsage;
  }
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point from) {
    return std::chrono::duration<double>(Clock::now() - from).count();
  };
  auto start = Clock::now();
  TangentDump dump = readTangentDump(options.directory);
  const double readSeconds = seconds(start);
  SystemMatrices system;
  system.free = std::move(dump.matrix);
  system.symmetric = dump.symmetric;
  system.patternVersion = 1;
  TangentSolver solver(*method);
  solver.setLayout(dump.layout);
  solver.setForcing(options.rtol);
  std::string fallback;
  solver.setNotifier([&](const std::string& line) {
    if (line.rfind("linear solver: ", 0) != 0) fallback = line;
  });
  std::string error;
  Eigen::VectorXd x;
  // CPU seconds as well as wall seconds: on a shared machine the wall clock measures the load.
  const auto cpuSeconds = [] { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; };
  double cpuFactorize = 0, cpuSolve = 0;
  start = Clock::now();
  try {
    double cpu = cpuSeconds();
    solver.factorize(system);
    cpuFactorize = cpuSeconds() - cpu;
    cpu = cpuSeconds();
    x = solver.solve(dump.rhs);
    cpuSolve = cpuSeconds() - cpu;
  } catch (const std::exception& failure) {
    error = failure.what();
    std::replace(error.begin(), error.end(), '"', '\'');  // stays a JSON string
  }
  const double totalSeconds = seconds(start);
  const LinearSolverStatistics work = solver.statistics();
  const double residual = x.size() ? (dump.rhs - system.free * x).norm() / dump.rhs.norm() : -1.0;
  fmt::print(
      "{{\"solver\": \"{}\", \"backend\": \"{}\", \"equations\": {}, \"nonzeros\": {}, "
      "\"symmetric\": {}, \"read_s\": {:.3f}, \"analysis_s\": {:.3f}, \"factor_s\": {:.3f}, "
      "\"solve_s\": {:.3f}, \"total_s\": {:.3f}, \"krylov_iterations\": {}, "
      "\"relative_residual\": {:.3e}, \"fallback\": {}, \"cpu_factorize_s\": {:.3f}, "
      "\"cpu_solve_s\": {:.3f}, \"error\": \"{}\"}}\n",
      options.solver, solver.activeBackend(), system.free.rows(), system.free.nonZeros(),
      system.symmetric ? "true" : "false", readSeconds, work.analysisSeconds,
      work.factorizationSeconds, work.solveSeconds, totalSeconds, work.krylovIterations, residual,
      fallback.empty() ? "false" : "true", cpuFactorize, cpuSolve, error);
  return error.empty() ? kExitOk : kExitInternal;
}

}  // namespace cc::app
