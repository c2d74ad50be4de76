// Load stepper: cut-back and regrowth landing exactly on nominal times, no time drift, the
// cut-back limit, singular systems, interruption, output selection and restart.
#include <gtest/gtest.h>

#include "solver/load_stepper.hpp"
#include "spring_chain.hpp"

namespace cc {
namespace {

using test::RecordingObserver;
using test::SpringChain;
using test::SpringLaw;

PhaseSpec phase(int steps, double dt) {
  PhaseSpec spec;
  spec.steps = steps;
  spec.dt = dt;
  spec.cutback.growAfter = 2;
  return spec;
}

std::vector<double> convergedTimes(const RecordingObserver& observer) {
  std::vector<double> times;
  for (const auto& step : observer.steps) times.push_back(step.time);
  return times;
}

SpringChain linearChain() {
  return SpringChain(3, SpringLaw::linear(1.0), [](double t) { return 0.1 * t; });
}

TEST(LoadStepper, CutsBackUntilTheStepPassesRegrowsAndLandsOnNominalTimes) {
  SpringChain chain = linearChain();
  // Steps longer than 0.3 fail while t <= 1: dt = 1 and 0.5 fail, 0.25 passes; after two easy
  // steps dt = 0.5 fails again at t = 1; beyond t = 1 regrowth reaches dt = 1.
  chain.items().failThreshold = 0.3;
  chain.items().failFrom = 0.0;
  chain.items().failUntil = 1.0;
  RecordingObserver observer;
  LoadStepper stepper(chain, observer, {phase(4, 1.0)});
  const RunSummary summary = stepper.run();
  ASSERT_EQ(summary.outcome, RunSummary::Outcome::Completed) << summary.message;
  EXPECT_EQ(convergedTimes(observer),
            (std::vector<double>{0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0}));
  EXPECT_EQ(summary.finalTime, 4.0);
  EXPECT_EQ(summary.stepsConverged, 8);
  EXPECT_EQ(summary.totalCutbacks, 3);
  EXPECT_EQ(chain.restores, 3);
  EXPECT_EQ(chain.commits, 8);
  ASSERT_EQ(observer.cutbacks.size(), 3u);
  EXPECT_EQ(observer.cutbacks[0].time, 1.0);
  EXPECT_EQ(observer.cutbacks[0].newDt, 0.5);
  EXPECT_EQ(observer.cutbacks[1].time, 0.5);
  EXPECT_EQ(observer.cutbacks[1].newDt, 0.25);
  EXPECT_EQ(observer.cutbacks[2].time, 1.0);
  EXPECT_EQ(observer.cutbacks[2].step, 3);
  // Step 1 was tried at dt = 1, 0.5 (failing in the assembly, before any solve is logged)
  // and converged at dt = 0.25 in attempt 2.
  EXPECT_EQ(observer.iterations.front().step, 1);
  EXPECT_EQ(observer.iterations.front().attempt, 2);
  EXPECT_EQ(observer.iterations.front().time, 0.25);
  EXPECT_EQ(observer.steps[0].cutbacks, 2);
  EXPECT_EQ(observer.steps[2].cutbacks, 1);
  // The prescribed end follows 0.1 t exactly at the final time.
  EXPECT_NEAR(observer.steps.back().displacement[9], 0.4, 1e-15);
  const SolverStatistics statistics = stepper.statistics();
  EXPECT_EQ(statistics.steps, 8);
  EXPECT_EQ(statistics.cutbacks, 3);
  EXPECT_EQ(statistics.linear.analyses, 1);  // the pattern never changed
  EXPECT_EQ(statistics.linear.factorizations, statistics.iterations);
}

TEST(LoadStepper, StepEndsDoNotDriftOverManySteps) {
  SpringChain chain = linearChain();
  RecordingObserver observer;
  LoadStepper stepper(chain, observer, {phase(10, 0.1), phase(4, 0.05)});
  const RunSummary summary = stepper.run();
  ASSERT_EQ(summary.outcome, RunSummary::Outcome::Completed);
  const std::vector<double> times = convergedTimes(observer);
  ASSERT_EQ(times.size(), 14u);
  for (int k = 1; k <= 10; ++k) EXPECT_EQ(times[k - 1], k * 0.1);
  EXPECT_EQ(times[9], 1.0);  // adding 0.1 ten times would give 0.9999999999999999
  EXPECT_DOUBLE_EQ(summary.finalTime, 1.2);
}

TEST(LoadStepper, StopsAfterTheCutbackLimitKeepingConvergedSteps) {
  SpringChain chain = linearChain();
  chain.items().failThreshold = 0.0;  // every step ending after t = 2 fails
  chain.items().failFrom = 2.0;
  RecordingObserver observer;
  PhaseSpec spec = phase(5, 1.0);
  spec.cutback.maxCutbacks = 3;
  LoadStepper stepper(chain, observer, {spec});
  const RunSummary summary = stepper.run();
  EXPECT_EQ(summary.outcome, RunSummary::Outcome::Diverged);
  EXPECT_EQ(summary.stepsConverged, 2);
  EXPECT_EQ(summary.finalTime, 2.0);
  EXPECT_EQ(summary.totalCutbacks, 3);
  EXPECT_EQ(observer.cutbacks.size(), 3u);
  EXPECT_EQ(chain.restores, 4);  // once per failed attempt
  EXPECT_NE(summary.message.find("t = 2.125"), std::string::npos) << summary.message;
  EXPECT_NE(summary.message.find("dt = 0.125"), std::string::npos) << summary.message;
  EXPECT_NE(summary.message.find("springs item 0: step too large"), std::string::npos)
      << summary.message;
}

TEST(LoadStepper, UnsupportedChainStopsAsSingular) {
  // No support in x: a rigid-body mode; smaller steps cannot help.
  SpringChain chain(
      3, SpringLaw::linear(1.0), {}, [](double t) { return t; }, false);
  RecordingObserver observer;
  LoadStepper stepper(chain, observer, {phase(2, 1.0)});
  const RunSummary summary = stepper.run();
  EXPECT_EQ(summary.outcome, RunSummary::Outcome::Singular);
  EXPECT_EQ(summary.stepsConverged, 0);
  EXPECT_EQ(summary.totalCutbacks, 1);
  EXPECT_EQ(chain.restores, 2);
  EXPECT_NE(summary.message.find("singular"), std::string::npos) << summary.message;
}

TEST(LoadStepper, InterruptDiscardsTheUnconvergedStep) {
  SpringChain chain = linearChain();
  RecordingObserver observer;
  observer.stopAfterIterations = 3;  // energy criterion: 2 iterations per linear step
  LoadStepper stepper(chain, observer, {phase(4, 1.0)});
  const RunSummary summary = stepper.run();
  EXPECT_EQ(summary.outcome, RunSummary::Outcome::Interrupted);
  EXPECT_EQ(summary.stepsConverged, 1);
  EXPECT_EQ(summary.finalTime, 1.0);
  EXPECT_EQ(chain.restores, 1);
  EXPECT_EQ(observer.iterations.back().step, 2);
}

TEST(LoadStepper, OutputEveryKStepsAndAlwaysAtThePhaseEnd) {
  SpringChain chain = linearChain();
  RecordingObserver observer;
  PhaseSpec spec = phase(5, 1.0);
  spec.outputEvery = 2;
  LoadStepper stepper(chain, observer, {spec});
  ASSERT_EQ(stepper.run().outcome, RunSummary::Outcome::Completed);
  std::vector<bool> written;
  for (const auto& step : observer.steps) written.push_back(step.written);
  EXPECT_EQ(written, (std::vector<bool>{false, true, false, true, true}));
}

TEST(LoadStepper, RestartFromAStoredStepReproducesTheRun) {
  auto hardening = [] {
    return SpringChain(3, SpringLaw::cubic(1.0, 1.0), {}, [](double t) { return 0.5 * t; });
  };
  SpringChain full = hardening();
  RecordingObserver fullObserver;
  LoadStepper fullStepper(full, fullObserver, {phase(4, 0.5)});
  ASSERT_EQ(fullStepper.run().outcome, RunSummary::Outcome::Completed);

  SpringChain restarted = hardening();
  RecordingObserver observer;
  LoadStepper stepper(restarted, observer, {phase(4, 0.5)});
  StartState start;
  start.step = 2;
  start.time = fullObserver.steps[1].time;
  start.displacement = fullObserver.steps[1].displacement;
  const RunSummary summary = stepper.run(start);
  ASSERT_EQ(summary.outcome, RunSummary::Outcome::Completed);
  ASSERT_EQ(observer.steps.size(), 2u);
  EXPECT_EQ(observer.steps[0].step, 3);
  EXPECT_EQ(observer.steps[1].time, 2.0);
  EXPECT_LT((observer.steps[1].displacement - fullObserver.steps[3].displacement).norm(), 1e-14);
  // The tip force 0.5 t = 1 at t = 2 stretches each spring to d + d^3 = 1.
  const double extension = 0.6823278038280193;  // real root of d^3 + d - 1
  EXPECT_NEAR(observer.steps[1].displacement[9], 3 * extension, 1e-12);
}

}  // namespace
}  // namespace cc
