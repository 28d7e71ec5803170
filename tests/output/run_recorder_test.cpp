// RunRecorder: the event tally, stop requests, interrupts and progress reports a
// solver's main loop relies on; the streaming recorder's files before and after commit.
#include "rigidity/run_recorder.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mini_json.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"

namespace rigidity {
namespace {

namespace fs = std::filesystem;

TEST(RunRecorder, CountsEventsByKindAndKeepsTheFirstOnes) {
  MemoryRecorder recorder;
  const long n = static_cast<long>(RunRecorder::kFirstEvents) + 50;
  for (long i = 0; i < n; ++i)
    recorder.event(RunEvent{static_cast<double>(i), i % 3 == 0 ? "contact" : "separation", 0.0, {"bar"}});
  EXPECT_EQ(recorder.first_events().size(), RunRecorder::kFirstEvents);
  EXPECT_EQ(recorder.first_events().back().t, static_cast<double>(RunRecorder::kFirstEvents - 1));
  const std::vector<std::pair<std::string, long>> expected{{"contact", 50}, {"separation", 100}};
  EXPECT_EQ(recorder.event_counts(), expected);

  RunResult result;
  recorder.complete(result, 7.0);
  EXPECT_EQ(result.status, "ok");
  EXPECT_EQ(result.t_reached, 7.0);
  EXPECT_EQ(static_cast<long>(result.events.size()), n);  // in memory: every event
  EXPECT_EQ(result.event_counts, expected);
}

TEST(RunRecorder, AStopRequestEndsTheRunAtTheNextPoll) {
  MemoryRecorder recorder;
  EXPECT_FALSE(recorder.poll(0.5, 10, 100));
  recorder.stop("more than solver.max_fronts");
  recorder.stop("a later reason is not kept");
  EXPECT_FALSE(recorder.stopped());  // the solver finishes what it is doing first
  EXPECT_TRUE(recorder.poll(0.75, 10, 101));
  EXPECT_TRUE(recorder.stopped());
  EXPECT_EQ(recorder.status(), RunStatus::stopped);
  EXPECT_EQ(recorder.t_reached(), 0.75);

  RunResult result;
  recorder.complete(result, 2.0);
  EXPECT_EQ(result.status, "stopped");
  EXPECT_EQ(result.t_reached, 0.75);
  EXPECT_EQ(result.stop_reason, "more than solver.max_fronts");
}

TEST(RunRecorder, AnInterruptEndsTheRunAtTheNextPoll) {
  MemoryRecorder recorder;
  EXPECT_FALSE(recorder.poll(0.1, 1, 1));
  request_interrupt();
  EXPECT_TRUE(interrupt_requested());
  EXPECT_TRUE(recorder.poll(0.2, 1, 2));
  clear_interrupt();
  EXPECT_EQ(recorder.status(), RunStatus::interrupted);
  RunResult result;
  recorder.complete(result, 1.0);
  EXPECT_EQ(result.status, "interrupted");
  EXPECT_EQ(result.t_reached, 0.2);
}

TEST(RunRecorder, ReportsProgressOnlyOnceTheRunHasTakenItsDelay) {
  using Clock = std::chrono::steady_clock;
  std::vector<RunProgress> reports;
  MemoryRecorder recorder;
  recorder.on_progress([&](const RunProgress& p) { reports.push_back(p); }, 0.02, 0.005);
  const Clock::time_point start = Clock::now();
  double t = 0.0;
  long polls = 0;
  while (Clock::now() - start < std::chrono::milliseconds(150)) {
    t += 1e-6;
    ASSERT_FALSE(recorder.poll(t, 42, ++polls));
  }
  ASSERT_FALSE(reports.empty());
  EXPECT_GE(reports.front().elapsed_s, 0.02);
  EXPECT_EQ(reports.front().fronts_alive, 42);
  EXPECT_GT(reports.front().t, 0.0);
  EXPECT_LT(reports.size(), 100u);  // about every 5 ms over 130 ms, not every poll
  for (std::size_t i = 1; i < reports.size(); ++i) EXPECT_GT(reports[i].t, reports[i - 1].t);

  MemoryRecorder patient;
  bool called = false;
  patient.on_progress([&](const RunProgress&) { called = true; }, 10.0);
  for (int i = 0; i < 100000; ++i) ASSERT_FALSE(patient.poll(i, -1, i));
  EXPECT_FALSE(called);  // a short run shows no progress
}

class StreamingFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() / ("rigidity_recorder_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(base_);
    fs::create_directories(base_);
  }
  void TearDown() override { fs::remove_all(base_); }

  static Scene scene() {
    Scene s;
    s.name = "streamed";
    BodyDecl bar;
    bar.name = "bar";
    s.bodies.push_back(bar);
    s.t_end = 1.0;
    s.outputs.probes.push_back(ProbeDecl{"mid", "bar", 0.5, {Quantity::p}, 1e-6, {}, std::nullopt});
    s.resolver = [] { return std::string("name: streamed\n"); };
    return s;
  }
  /// The one entry of base_ whose name starts with `prefix`, or "".
  [[nodiscard]] fs::path entry_starting(const std::string& prefix) const {
    for (const auto& e : fs::directory_iterator(base_))
      if (e.path().filename().string().rfind(prefix, 0) == 0) return e.path();
    return {};
  }
  fs::path base_;
};

TEST_F(StreamingFiles, RowsReachTheDiskBeforeTheRunEndsAndTheDirectoryOnlyAtCommit) {
  const Scene s = scene();
  const fs::path dir = base_ / "run";
  StreamingRecorder recorder(s, dir.string());
  for (int i = 0; i < 200000; ++i) recorder.probe(ProbeSample{i * 1e-6, 0, Quantity::p, 1.0});
  EXPECT_FALSE(fs::exists(dir));
  const fs::path temporary = entry_starting("run.tmp-");
  ASSERT_FALSE(temporary.empty());
  EXPECT_GT(fs::file_size(temporary / "probes.csv"), 1000000u);  // written as produced, not kept

  RunResult result;
  recorder.complete(result, s.t_end);
  recorder.commit(result);
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
  EXPECT_TRUE(entry_starting("run.tmp-").empty());
  std::ifstream in(dir / "probes.csv");
  long lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 200001);
}

TEST_F(StreamingFiles, AStoppedRunSaysSoInItsSummary) {
  const Scene s = scene();
  StreamingRecorder recorder(s, (base_ / "run").string());
  recorder.probe(ProbeSample{0.0, 0, Quantity::p, 1.0});
  recorder.stop("more than solver.max_interactions = 10 interactions");
  ASSERT_TRUE(recorder.poll(0.25, 3, 11));
  RunResult result;
  recorder.complete(result, s.t_end);
  recorder.commit(result);

  std::ifstream in(base_ / "run" / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  const mini_json::Value doc = mini_json::parse(text.str());
  EXPECT_EQ(doc["status"].string, "stopped");
  EXPECT_EQ(doc["stop_reason"].string, "more than solver.max_interactions = 10 interactions");
  EXPECT_EQ(doc["t_end"].number, 1.0);
  EXPECT_EQ(doc["t_reached"].number, 0.25);
}

TEST_F(StreamingFiles, ANonFiniteValueFailsTheRunAndLeavesNothing) {
  const Scene s = scene();
  const fs::path dir = base_ / "a" / "b" / "run";
  try {
    StreamingRecorder recorder(s, dir.string());
    recorder.probe(ProbeSample{0.0, 0, Quantity::p, 1.0});
    recorder.event(RunEvent{0.5, "contact", std::numeric_limits<double>::quiet_NaN(), {"bar"}});
    FAIL() << "a NaN was streamed";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("events.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("nothing was written to"), std::string::npos) << what;
  }
  EXPECT_TRUE(fs::is_empty(base_));  // nor the parents made for it
}

}  // namespace
}  // namespace rigidity
