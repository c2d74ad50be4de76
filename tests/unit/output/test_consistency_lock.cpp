// ConsistencyLock (issue 15): a reader of a file in progress waits for the writer's flush, and a
// writer waits for readers, each for a bounded time; the lock is independent of the writer's
// flock. Open-file-description locks conflict between two descriptions of the same file even in
// one process, so both sides are exercised here without a second process.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "output/hdf5_io.hpp"
#include "output/results_file_guard.hpp"

namespace cc::test {
namespace {

std::string scratchFile(const char* name) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     (std::string("covcontact_consistency_") + name + ".h5");
  std::filesystem::remove(path);
  return path.string();
}

double secondsOf(const std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(ConsistencyLock, AReaderWaitsForTheWritersChangeAndThenGivesUpWithAMessage) {
  const std::string path = scratchFile("reader_waits");
  const ResultsFileLock writer(path);  // the writer's flock: readers are not stopped by it
  EXPECT_TRUE(ConsistencyLock::forReading(path, 0.05).held());
  {
    const ConsistencyLock change = writer.beginChange();
    ASSERT_TRUE(change.held());
    const auto start = std::chrono::steady_clock::now();
    try {
      (void)ConsistencyLock::forReading(path, 0.2);
      FAIL() << "a reader got the lock during the writer's change";
    } catch (const OutputError& error) {
      EXPECT_NE(std::string(error.what()).find("did not finish a flush in 0.2 s"),
                std::string::npos)
          << error.what();
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
    EXPECT_GE(secondsOf(start), 0.2);
    EXPECT_LT(secondsOf(start), 5.0);
  }
  EXPECT_TRUE(ConsistencyLock::forReading(path, 0.05).held()) << "released after the change";
  std::filesystem::remove(path);
}

TEST(ConsistencyLock, ReadersShareTheLockAndAWriterWaitsForThemBoundedly) {
  const std::string path = scratchFile("writer_waits");
  const ResultsFileLock writer(path);
  ConsistencyLock first = ConsistencyLock::forReading(path, 0.05);
  ConsistencyLock second = ConsistencyLock::forReading(path, 0.05);
  EXPECT_TRUE(first.held());
  EXPECT_TRUE(second.held()) << "two readers at once";
  EXPECT_FALSE(ConsistencyLock::forWriting(-1).held()) << "a rank without the file";
  // Readers hold the byte: the writer gives up after its patience (and then writes anyway).
  auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(writer.beginChange(0.1).held());
  EXPECT_GE(secondsOf(start), 0.1);
  EXPECT_LT(secondsOf(start), 5.0);
  first = ConsistencyLock();
  EXPECT_FALSE(writer.beginChange(0.05).held()) << "one reader is still there";
  {
    const ConsistencyLock third = std::move(second);
    EXPECT_TRUE(third.held()) << "moved, not released";
    EXPECT_FALSE(second.held());
  }
  EXPECT_TRUE(writer.beginChange(0.05).held()) << "every reader gone";
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cc::test
