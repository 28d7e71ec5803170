// rigidity plot, end to end: a run's outputs drawn with gnuplot, missing files skipped,
// a missing or failing gnuplot reported with exit 1.
#include <sys/stat.h>

#include <cstdlib>
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
  EXPECT_TRUE(contains(xt, "strcol(5) eq 'contact'"));
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
}

TEST_F(PlotTest, WritesElsewhereWithScriptsThatRerun) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  const CliOutcome r = rigidity("plot run --out pictures");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(is_png(dir() / "pictures" / "xt.png"));
  EXPECT_FALSE(fs::exists(dir() / "run" / "xt.png"));
  EXPECT_TRUE(contains(read_text(dir() / "pictures" / "xt.gp"), "'../run/fronts.csv'"));
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
  EXPECT_TRUE(contains(rigidity("--help").out, "rigidity plot"));
}

}  // namespace
}  // namespace rigidity::testing
