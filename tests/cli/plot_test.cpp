// rigidity plot, end to end: a run's outputs drawn with gnuplot, missing files skipped,
// a missing or failing gnuplot reported with exit 1.
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "run_cli.hpp"

namespace rigidity::testing {
namespace {

/// A run of the default scene (the paper's wall impact: probes, snapshots and fronts) in dir()/run.
class PlotTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const CliOutcome r = rigidity("run --out run");
    ASSERT_EQ(r.exit_status, 0) << r.err;
    for (const char* file : {"fronts.csv", "probes.csv", "snapshots.csv"})
      ASSERT_TRUE(fs::is_regular_file(dir() / "run" / file)) << file;
  }
};

TEST_F(PlotTest, DrawsTheXtDiagramProbesAndSnapshots) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  const CliOutcome r = rigidity("plot run");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // gnuplot had nothing to complain about
  for (const char* plot : {"xt", "probes", "snapshots"}) {
    EXPECT_TRUE(is_png(dir() / "run" / (std::string(plot) + ".png")));
    EXPECT_TRUE(fs::is_regular_file(dir() / "run" / (std::string(plot) + ".gp"))) << plot;
  }
  EXPECT_TRUE(contains(r.out, "xt.png, probes.png, snapshots.png, snapshots_lab.png, animation.gif"));
  // The animation: a GIF of 60 frames, the x-t diagram up to each frame's time and the fronts
  // where they are then.
  const std::string gif = read_text(dir() / "run" / "animation.gif");
  EXPECT_EQ(gif.substr(0, 6), "GIF89a");
  const std::string animation = read_text(dir() / "run" / "animation.gp");
  EXPECT_TRUE(contains(animation, "do for [frame = 0:59]"));
  EXPECT_TRUE(contains(animation, "set terminal gif animate"));
  // The fronts of the paper's impact are contacts (linearly degenerate) and body ends.
  const std::string xt = read_text(dir() / "run" / "xt.gp");
  EXPECT_TRUE(contains(xt, "data = 'xt_fronts.csv'"));
  EXPECT_TRUE(contains(xt, "data index 0 using"));
  EXPECT_TRUE(contains(xt, "set key below"));  // the key does not eat the diagram
  EXPECT_TRUE(
      contains(read_text(dir() / "run" / "xt_fronts.csv"), "one block per kind (gnuplot index 0, 1, ...): contact"));
  EXPECT_TRUE(contains(xt, "title 'jump at c_s (linearly degenerate: compression or release)'"));
  EXPECT_TRUE(contains(xt, "title 'body end'"));
  EXPECT_FALSE(contains(xt, "title 'shock'"));  // only the kinds present are listed
  // A front-tracking profile is a staircase of jumps: drawn as steps, outside the key.
  const std::string snapshots = read_text(dir() / "run" / "snapshots.gp");
  EXPECT_TRUE(contains(snapshots, "strcol(4) eq 'p' ? $5 : NaN) with steps")) << snapshots;
  EXPECT_TRUE(contains(snapshots, "strcol(4) eq 'x' ? $5 : NaN) with lines")) << snapshots;  // continuous
  EXPECT_TRUE(contains(snapshots, "set key outside"));
  // The same profiles against the lab position (the paper's snapshots sample x): p at the
  // sample's lab position, from the same snapshot.
  EXPECT_TRUE(is_png(dir() / "run" / "snapshots_lab.png"));
  const std::string lab = read_text(dir() / "run" / "snapshots_lab.csv");
  EXPECT_EQ(lab.substr(0, lab.find('\n')), "t,body,x,quantity,value");
  EXPECT_TRUE(contains(lab, "\n0.5,bar,")) << lab;
  EXPECT_EQ(lab.find(",x,", lab.find('\n')), std::string::npos) << lab;  // x against x says nothing
  // One panel per probe quantity: p, v, s of the wall probe, v, x of the rear one.
  const std::string probes = read_text(dir() / "run" / "probes.gp");
  EXPECT_TRUE(contains(probes, "set multiplot layout 2,2"));
  EXPECT_TRUE(contains(probes, "strcol(2) eq 'rear' && strcol(3) eq 'x'"));
  // Exact jumps as steps, the continuous lab position as a line.
  EXPECT_TRUE(contains(probes, "strcol(3) eq 'p' ? $4 : NaN) with steps")) << probes;
  EXPECT_TRUE(contains(probes, "strcol(3) eq 'x' ? $4 : NaN) with lines")) << probes;
}

TEST_F(PlotTest, SkipsTheAnimationWhenAsked) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  const CliOutcome r = rigidity("plot run --no-animation");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(is_png(dir() / "run" / "xt.png"));
  EXPECT_FALSE(fs::exists(dir() / "run" / "animation.gif"));
  EXPECT_FALSE(contains(r.out, "animation"));
}

TEST_F(CliTest, PlotDecimatesMillionsOfFrontsToWhatCanBeSeen) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  // 100 fronts of 1500 pieces each, every piece shorter than a pixel in t and in x, plus every
  // piece once more: 300 000 segments, of which a 800 x 560 grid can show far fewer.
  fs::create_directories(dir() / "big");
  {
    std::ofstream csv(dir() / "big" / "fronts.csv", std::ios::binary);
    csv << "t0,x0,t1,x1,kind,family\n";
    for (int copy = 0; copy < 2; ++copy)
      for (int front = 0; front < 100; ++front)
        for (int piece = 0; piece < 1500; ++piece) {
          const double t0 = piece / 1500.0, t1 = (piece + 1) / 1500.0;
          csv << t0 << ',' << front * 0.02 + 0.3 * t0 << ',' << t1 << ',' << front * 0.02 + 0.3 * t1
              << (front % 2 == 0 ? ",shock,1\n" : ",rarefaction,-1\n");
        }
  }
  const auto start = std::chrono::steady_clock::now();
  const CliOutcome r = rigidity("plot big");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_LT(seconds, 20.0);
  EXPECT_TRUE(is_png(dir() / "big" / "xt.png"));
  // What gnuplot draws: at most one segment per cell a front crosses (560 in t, about 70 in x).
  const std::string data = read_text(dir() / "big" / "xt_fronts.csv");
  const long rows = std::count(data.begin(), data.end(), '\n') - 2;  // two comment lines
  EXPECT_GT(rows, 100 * 500);                                        // every front still drawn whole
  EXPECT_LT(rows, 100 * 800);
  EXPECT_TRUE(contains(read_text(dir() / "big" / "xt.gp"), "300000 segments"));
  // So many segments are not animated unless asked for.
  EXPECT_TRUE(contains(r.out, "skipped animation.gif")) << r.out;
  EXPECT_FALSE(fs::exists(dir() / "big" / "animation.gif"));
}

TEST_F(PlotTest, WritesElsewhereWithScriptsThatRerun) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  const CliOutcome r = rigidity("plot run --out pictures");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(is_png(dir() / "pictures" / "xt.png"));
  EXPECT_FALSE(fs::exists(dir() / "run" / "xt.png"));
  EXPECT_TRUE(fs::is_regular_file(dir() / "pictures" / "xt_fronts.csv"));
  EXPECT_TRUE(contains(read_text(dir() / "pictures" / "probes.gp"), "'../run/probes.csv'"));
  // The kept script draws the same picture when rerun by hand in its directory.
  fs::remove(dir() / "pictures" / "xt.png");
  const std::string rerun = "cd " + shell_quote((dir() / "pictures").string()) + " && gnuplot xt.gp 2>&1";
  EXPECT_EQ(std::system(rerun.c_str()), 0);
  EXPECT_TRUE(is_png(dir() / "pictures" / "xt.png"));
}

TEST_F(PlotTest, SkipsAMissingCsv) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  fs::remove(dir() / "run" / "probes.csv");
  const CliOutcome r = rigidity("plot run");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "skipped probes.png"));
  EXPECT_FALSE(fs::exists(dir() / "run" / "probes.png"));
  EXPECT_TRUE(is_png(dir() / "run" / "xt.png"));
  EXPECT_TRUE(is_png(dir() / "run" / "snapshots.png"));
}

TEST_F(PlotTest, WithoutGnuplotExitsOneWithAClearMessage) {
  CliOutcome r;
  {
    const ScopedPath no_path("");
    r = rigidity("plot run");
  }
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_TRUE(contains(r.err, "gnuplot not found on PATH"));
  EXPECT_TRUE(contains(r.err, "apt-get install gnuplot-nox"));
  EXPECT_FALSE(contains(r.err, "internal error"));
  EXPECT_FALSE(fs::exists(dir() / "run" / "xt.png"));
}

TEST_F(PlotTest, AFailingGnuplotIsReported) {
  // A stand-in gnuplot that fails: its exit status and messages reach the user.
  const fs::path bin = dir() / "bin";
  fs::create_directories(bin);
  write_file("bin/gnuplot", "#!/bin/sh\necho 'line 1: unknown terminal' >&2\nexit 3\n");
  ::chmod((bin / "gnuplot").c_str(), 0755);
  CliOutcome r;
  {
    const ScopedPath fake_path(bin.string() + ":/usr/bin:/bin");
    r = rigidity("plot run");
  }
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_TRUE(contains(r.err, "gnuplot failed on"));
  EXPECT_TRUE(contains(r.err, "exit status 3"));
  EXPECT_TRUE(contains(r.err, "unknown terminal"));
}

TEST_F(CliTest, PlotRejectsWhatIsNotARunDirectory) {
  CliOutcome r = rigidity("plot nowhere");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "nowhere not found"));

  fs::create_directories(dir() / "empty");
  r = rigidity("plot empty");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "not a run directory"));

  r = rigidity("plot");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "usage: rigidity plot"));
}

TEST_F(CliTest, PlotHasHelp) {
  const CliOutcome r = rigidity("plot --help");
  EXPECT_EQ(r.exit_status, 0);
  EXPECT_TRUE(contains(r.out, "usage: rigidity plot RUN_DIR"));
  // Every image it draws.
  for (const char* image : {"xt.png", "probes.png", "snapshots.png", "snapshots_lab.png", "animation.gif"})
    EXPECT_TRUE(contains(r.out, image)) << image;
  EXPECT_TRUE(contains(r.out, "--no-animation"));
  EXPECT_TRUE(contains(rigidity("--help").out, "rigidity plot"));
}

}  // namespace
}  // namespace rigidity::testing
