// Restart support in-process (issue 7): the element (EAS) and contact (STAS) history a model
// saves is restored exactly into a fresh model, a mismatching history is refused with its name,
// and a run continued from a saved step ends exactly where the uninterrupted run ends.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "cube_decks.hpp"
#include "deck/deck_parser.hpp"
#include "output/restart_io.hpp"
#include "output/results_layout.hpp"
#include "output/results_reader.hpp"
#include "stress_support.hpp"

namespace cc::test {
namespace {

// Saves the model's history, displacement and next step size at one converged step.
class SavingObserver : public StepObserver {
 public:
  SavingObserver(Model& model, int saveAt) : model_(model), saveAt_(saveAt) {}
  void attach(const LoadStepper& stepper) { stepper_ = &stepper; }
  void stepConverged(int step, double time, int, int, const Eigen::VectorXd& displacement,
                     const Eigen::VectorXd& internalForce, bool) override {
    if (step == saveAt_) {
      saved = model_.saveHistory();
      saved.displacement = displacement;
      saved.stepFraction = stepper_->nextStepSize().fraction;
      saved.easySteps = stepper_->nextStepSize().easySteps;
      savedTime = time;
    }
    lastDisplacement = displacement;
    lastForce = internalForce;
    lastContact = model_.stepRecord(step, time, 0, 0, displacement, internalForce, false).contact;
    lastStep = step;
  }

  RestartRecord saved;
  double savedTime = 0;
  Eigen::VectorXd lastDisplacement, lastForce;
  std::vector<ContactPairRecord> lastContact;
  int lastStep = 0;

 private:
  Model& model_;
  int saveAt_;
  const LoadStepper* stepper_ = nullptr;
};

TEST(History, SavedElementAndContactHistoryRestoresExactlyIntoAFreshModel) {
  const ProblemSpec spec = parseDeck(stressDeck("thin_shell_on_cylinder"));
  const std::unique_ptr<Model> model = buildModel(spec);
  SavingObserver observer(*model, 7);
  LoadStepper stepper(*model, observer, spec.phases);
  observer.attach(stepper);
  ASSERT_EQ(stepper.run().outcome, RunSummary::Outcome::Completed);
  const RestartRecord& saved = observer.saved;
  ASSERT_EQ(saved.elementHistory.size(), 1u);
  ASSERT_EQ(saved.contactHistory.size(), 1u);
  // Solid-shell EAS parameters and STAS history (master point, surface offset) are not trivial.
  EXPECT_GT(Eigen::Map<const Eigen::VectorXd>(saved.elementHistory[0].second.data(),
                                              saved.elementHistory[0].second.size())
                .cwiseAbs()
                .maxCoeff(),
            0.0);
  EXPECT_GT(saved.contactHistory[0].second.cwiseAbs().maxCoeff(), 0.0);

  const std::unique_ptr<Model> fresh = buildModel(spec);
  fresh->restoreHistory(saved);
  const RestartRecord again = fresh->saveHistory();
  EXPECT_EQ(again.elementHistory[0].second, saved.elementHistory[0].second);
  EXPECT_EQ(again.contactHistory[0].second, saved.contactHistory[0].second);

  // Continue from step 7: the remaining steps end exactly where the uninterrupted run ended.
  SavingObserver continued(*fresh, -1);
  LoadStepper restarted(*fresh, continued, spec.phases);
  continued.attach(restarted);
  StartState start;
  start.step = 7;
  start.time = observer.savedTime;
  start.displacement = saved.displacement;
  start.stepSize = {saved.stepFraction, saved.easySteps};
  ASSERT_EQ(restarted.run(start).outcome, RunSummary::Outcome::Completed);
  EXPECT_EQ(continued.lastStep, observer.lastStep);
  EXPECT_LT((continued.lastDisplacement - observer.lastDisplacement).cwiseAbs().maxCoeff(),
            1e-12 * observer.lastDisplacement.cwiseAbs().maxCoeff());
  EXPECT_LT((continued.lastContact[0].totalForce - observer.lastContact[0].totalForce).norm(),
            1e-10 * observer.lastContact[0].totalForce.norm());
}

// An augmented-Lagrangian run (issue 16, part 3) carries state beyond the point history: the
// committed normal multipliers (the next step's first guess) and the penalties aug_grow has
// raised. Before they were restart data, a continued run began again from zero multipliers and
// the deck's penalty, and ended elsewhere within the augmentation's tolerance. The small block at
// eps_ref / 100 raises its penalty in step 1 (and again in step 2): continued from step 1 it
// must end exactly where the uninterrupted run ends, with the same penalty.
TEST(History, AnAugmentedRunContinuesWithItsMultipliersAndRaisedPenalty) {
  const std::string path =
      std::string(COVCONTACT_SOURCE_DIR) + "/input/verification/contact/augmented_block.deck";
  const std::string text =
      replaceOnce(readText(path), "contact sts master=block_bottom slave=base_top mu=0.3",
                  "contact sts master=block_bottom slave=base_top mu=0.3 enforcement=augmented "
                  "eps_scale=0.01");
  const ProblemSpec spec = parseDeckText(text, path);
  const std::unique_ptr<Model> model = buildModel(spec);
  const int saveAt = 1;
  SavingObserver observer(*model, saveAt);
  LoadStepper stepper(*model, observer, spec.phases);
  observer.attach(stepper);
  ASSERT_EQ(stepper.run().outcome, RunSummary::Outcome::Completed);
  const double deckPenalty = model->contactPairs()[0]->config().referencePenalty * 0.01;
  const Eigen::MatrixXd& table = observer.saved.contactHistory[0].second;
  ASSERT_EQ(table.rows(), contact::ContactPair::kHistoryRows);
  EXPECT_GT(table.row(21).minCoeff(), 5 * deckPenalty);  // raised in step 1: the stored eps_n
  EXPECT_LT(table.row(20).minCoeff(), 0.0);              // some point carries a multiplier

  const std::unique_ptr<Model> fresh = buildModel(spec);
  fresh->restoreHistory(observer.saved);
  EXPECT_EQ(fresh->saveHistory().contactHistory[0].second, table);
  SavingObserver continued(*fresh, -1);
  LoadStepper restarted(*fresh, continued, spec.phases);
  continued.attach(restarted);
  StartState start;
  start.step = saveAt;
  start.time = observer.savedTime;
  start.displacement = observer.saved.displacement;
  start.stepSize = {observer.saved.stepFraction, observer.saved.easySteps};
  ASSERT_EQ(restarted.run(start).outcome, RunSummary::Outcome::Completed);
  EXPECT_EQ(continued.lastStep, observer.lastStep);
  EXPECT_LT((continued.lastDisplacement - observer.lastDisplacement).cwiseAbs().maxCoeff(),
            1e-12 * observer.lastDisplacement.cwiseAbs().maxCoeff());
  EXPECT_EQ(continued.lastContact[0].penaltyNormal, observer.lastContact[0].penaltyNormal);
  EXPECT_LT((continued.lastContact[0].totalForce - observer.lastContact[0].totalForce).norm(),
            1e-10 * observer.lastContact[0].totalForce.norm());
}

TEST(History, AHistoryThatDoesNotFitTheModelIsRefusedWithItsName) {
  const ProblemSpec spec = parseDeck(stressDeck("slide_off_edge"));
  const std::unique_ptr<Model> model = buildModel(spec);
  RestartRecord history = model->saveHistory();
  history.displacement = Eigen::VectorXd::Zero(3 * model->mesh().numNodes());
  RestartRecord wrongPoints = history;
  wrongPoints.contactHistory[0].second.conservativeResize(
      Eigen::NoChange, history.contactHistory[0].second.cols() - 1);
  try {
    model->restoreHistory(wrongPoints);
    ADD_FAILURE() << "a contact history with a point missing was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("contact pair 'interface'"), std::string::npos)
        << error.what();
  }
  RestartRecord missingBlock = history;
  missingBlock.elementHistory.erase(missingBlock.elementHistory.begin());
  EXPECT_THROW(model->restoreHistory(missingBlock), std::invalid_argument);
  RestartRecord badSegment = history;
  badSegment.contactHistory[0].second(1, 0) = 1e6;  // row 1: the master segment
  EXPECT_THROW(model->restoreHistory(badSegment), std::invalid_argument);
  RestartRecord badMultiplier = history;
  badMultiplier.contactHistory[0].second(20, 0) = 1.0;  // row 20: a normal multiplier, <= 0
  EXPECT_THROW(model->restoreHistory(badMultiplier), std::invalid_argument);
  RestartRecord badPenetration = history;
  badPenetration.contactHistory[0].second(27, 0) = -1.0;  // row 27: the deepest penetration
  EXPECT_THROW(model->restoreHistory(badPenetration), std::invalid_argument);
  // Restart data written before the penetration rows (27 rows), and before the multiplier and
  // penalty rows (20 rows), still continue.
  RestartRecord beforePenetration = history;
  beforePenetration.contactHistory[0].second.conservativeResize(27, Eigen::NoChange);
  EXPECT_NO_THROW(model->restoreHistory(beforePenetration));
  RestartRecord legacy = history;
  legacy.contactHistory[0].second.conservativeResize(20, Eigen::NoChange);
  EXPECT_NO_THROW(model->restoreHistory(legacy));
  EXPECT_NO_THROW(model->restoreHistory(history));
}

// The clamped cube (cube_decks.hpp) written to `directory`/`name` with the given steps lines.
void writeClampedCubeDeck(const std::string& directory, const std::string& name,
                          const std::string& steps) {
  std::ofstream(directory + "/" + name) << clampedCubeDeck(steps);
}

double chosenFactor(const ResultsReader& reader, int step) {
  return reader.numberAttribute(layout::stepGroupPath(step) + "/" + layout::kRestartGroup,
                                "viscous_factor");
}

// Runs `directory`/cube.deck to full.h5, and continued from its step 1 to continued.h5.
void runAndContinueFromStep1(const std::string& directory) {
  const CommandResult full = runCovcontact("run -q --threads 1 cube.deck -o full.h5", directory);
  ASSERT_EQ(full.exitCode, 0) << full.error;
  const CommandResult continued = runCovcontact(
      "run -q --threads 1 cube.deck --restart full.h5 --from-step 1 -o continued.h5", directory);
  ASSERT_EQ(continued.exitCode, 0) << continued.error;
}

// A phase with `stabilize_share` chooses its viscous factor after its first step. The factor is
// restart data, from the step that chose it on: continued from step 1, the run must go on with
// it and end exactly where the uninterrupted run ends. Choosing anew would solve step 2
// without stabilisation and take another factor from it.
TEST(History, AChosenViscousFactorIsRestartData) {
  const std::string directory = scratchDirectory("chosen_viscous_factor");
  writeClampedCubeDeck(directory, "cube.deck", "  steps 6 dt=0.25 stabilize_share=0.05\n");
  ASSERT_NO_FATAL_FAILURE(runAndContinueFromStep1(directory));

  const ResultsReader fullReader(directory + "/full.h5");
  const ResultsReader continuedReader(directory + "/continued.h5");
  EXPECT_GT(chosenFactor(fullReader, 1), 0.0);
  const std::string last = layout::stepGroupPath(6) + "/" + layout::kDisplacement;
  const Eigen::MatrixXd expected = fullReader.readMatrix(last);
  EXPECT_LT((continuedReader.readMatrix(last) - expected).cwiseAbs().maxCoeff(),
            1e-12 * expected.cwiseAbs().maxCoeff());
}

// Removes the energy account's restart data of `step` from `path`: a file as written before the
// fifty-first session.
void dropEnergyRestartData(const std::string& path, int step) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0) << path;
  const std::string group = layout::stepGroupPath(step) + "/" + layout::kRestartGroup;
  for (const char* name : {"energy_reactions", "energy_pairs"}) {
    EXPECT_GE(H5Ldelete(file, (group + "/" + name).c_str(), H5P_DEFAULT), 0) << name;
  }
  H5Fclose(file);
}

// A run continued from a file whose step holds no factor (here one written without
// stabilisation, its deck then given a stabilised phase) chooses it from its first step. The
// forces at the restart state are restart data, so that step's work is counted as in the
// uninterrupted run, (F_2 + F_3) . du_3 / 2, and the factors agree. From a file without them
// the step's work is counted with its own force, F_3 . du_3. Step 3 itself is the same in all
// three runs (solved without stabilisation from the same state), and the load is 10 t on free
// dofs only, so that factor stands to the uninterrupted one exactly as
// F_3 / ((F_2 + F_3) / 2) = 7.5 / 6.25. Taking the unknown force as zero instead would halve
// the work (ratio 0.6).
TEST(History, AFactorChosenAfterARestartCountsTheStepsWorkAsTheUninterruptedRun) {
  const std::string directory = scratchDirectory("factor_after_restart");
  const std::string phases = "  steps 2 dt=0.25\n  steps 4 dt=0.25 stabilize_share=0.05\n";
  writeClampedCubeDeck(directory, "plain.deck", "  steps 6 dt=0.25\n");
  writeClampedCubeDeck(directory, "stabilized.deck", phases);
  ASSERT_EQ(runCovcontact("run -q --threads 1 plain.deck -o plain.h5", directory).exitCode, 0);
  ASSERT_EQ(runCovcontact("run -q --threads 1 plain.deck -o old.h5", directory).exitCode, 0);
  ASSERT_NO_FATAL_FAILURE(dropEnergyRestartData(directory + "/old.h5", 2));
  ASSERT_EQ(runCovcontact("run -q --threads 1 stabilized.deck -o full.h5", directory).exitCode, 0);
  for (const char* from : {"plain", "old"}) {
    const CommandResult continued = runCovcontact(
        fmt::format("run -q --threads 1 stabilized.deck --restart {}.h5 --from-step 2 -o "
                    "continued_{}.h5",
                    from, from),
        directory);
    ASSERT_EQ(continued.exitCode, 0) << continued.error;
  }
  const double uninterrupted = chosenFactor(ResultsReader(directory + "/full.h5"), 3);
  const double afterRestart = chosenFactor(ResultsReader(directory + "/continued_plain.h5"), 3);
  const double fromOldFile = chosenFactor(ResultsReader(directory + "/continued_old.h5"), 3);
  EXPECT_NEAR(afterRestart / uninterrupted, 1.0, 1e-12);
  EXPECT_NEAR(fromOldFile / uninterrupted, 7.5 / 6.25, 1e-12);
}

// The energy account is restart data: a cube clamped at its bottom, pulled sideways by a load
// and pressed and dragged by a rigid plate with friction (the work of loads, supports and a
// moving rigid surface, and dissipation), continued from step 4, books every later step's
// energy as the uninterrupted run does. Before, the sums started again from zero and the first
// step's work took zero for the forces at the restart state.
TEST(History, AContinuedRunBooksItsEnergyAsTheUninterruptedRun) {
  const std::string directory = scratchDirectory("energy_after_restart");
  std::ofstream(directory + "/plate.deck")
      << "mesh \"" << COVCONTACT_SOURCE_DIR << "/meshes/cube.geo\" n=2\n"
      << "material m neohooke E=100 nu=0.3\n"
         "elements cube hex8 material=m\n"
         "fix zmin all\n"
         "load xmax fx \"2*t\" total\n"
         "rigid plate plane origin=(0,0,1) normal=(0,0,-1) uz \"-0.05*min(t/0.25,1)\" "
         "ux \"0.4*max(t-0.25,0)\"\n"
         "contact stas master=zmax slave=plate eps_n=1e4 eps_t=1e4 mu=0.3 name=top\n"
         "solve\n  steps 8 dt=0.125\nend\n";
  ASSERT_EQ(runCovcontact("run -q --threads 1 plate.deck -o full.h5", directory).exitCode, 0);
  const CommandResult continued = runCovcontact(
      "run -q --threads 1 plate.deck --restart full.h5 --from-step 4 -o continued.h5", directory);
  ASSERT_EQ(continued.exitCode, 0) << continued.error;
  const ResultsReader full(directory + "/full.h5");
  const ResultsReader restarted(directory + "/continued.h5");
  const std::string lastEnergy = layout::stepGroupPath(8) + "/energy";
  ASSERT_GT(full.numberAttribute(lastEnergy, "dissipation"),
            0.3 * full.numberAttribute(lastEnergy, "external_work"));
  for (int step = 5; step <= 8; ++step) {
    SCOPED_TRACE(step);
    const std::string energy = layout::stepGroupPath(step) + "/energy";
    for (const char* name : {"external_work", "strain_energy", "contact_energy", "dissipation",
                             "stabilization_dissipation", "balance", "quadrature_bound"}) {
      const double expected = full.numberAttribute(energy, name);
      EXPECT_NEAR(restarted.numberAttribute(energy, name), expected,
                  1e-12 * std::max(1.0, std::abs(expected)))
          << name;
    }
  }
}

// stabilize_on_failure: the free cube (singular without stabilisation) fails at step 1 and is
// retried stabilised; steps 2 and 3 keep the factor, step 3 is the third easy one, so step 4
// tries without it, fails and is retried; and so on: retries at steps 1, 4 and 7 of 8. Whether
// the next step starts stabilised is restart data. Continued from step 1, the run must retry
// only at steps 4 and 7, as the uninterrupted run did; starting step 2 without the factor
// would retry at 2, 5 and 8. Every step is solved stabilised from the same state in both, so
// the steps themselves must agree.
TEST(History, StabilisationOnFailureIsRestartData) {
  const std::string directory = scratchDirectory("stabilize_on_failure");
  std::ofstream(directory + "/cube.deck")
      << freeCubeDeck("  newton stabilize_on_failure=0.5\n", "10*t", "8 dt=0.125");
  ASSERT_NO_FATAL_FAILURE(runAndContinueFromStep1(directory));

  const ResultsReader fullReader(directory + "/full.h5");
  const ResultsReader continuedReader(directory + "/continued.h5");
  EXPECT_EQ(fullReader.numberAttribute("/summary", "stabilized_retries"), 3);
  EXPECT_EQ(continuedReader.numberAttribute("/summary", "stabilized_retries"), 2);
  const auto restartGroup = [](int step) {
    return layout::stepGroupPath(step) + "/" + layout::kRestartGroup;
  };
  // After step 1 one easy stabilised step is counted; after step 3 the run left the factor.
  EXPECT_EQ(fullReader.numberAttribute(restartGroup(1), "stabilized_easy_steps"), 1);
  EXPECT_FALSE(fullReader.hasAttribute(restartGroup(3), "stabilized_easy_steps"));
  for (int step = 2; step <= 8; ++step) {
    SCOPED_TRACE(step);
    const std::string path = layout::stepGroupPath(step);
    EXPECT_EQ(continuedReader.numberAttribute(path, "iterations"),
              fullReader.numberAttribute(path, "iterations"));
    const Eigen::MatrixXd expected = fullReader.readMatrix(path + "/" + layout::kDisplacement);
    EXPECT_LT((continuedReader.readMatrix(path + "/" + layout::kDisplacement) - expected)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12 * expected.cwiseAbs().maxCoeff());
  }
}

}  // namespace
}  // namespace cc::test
