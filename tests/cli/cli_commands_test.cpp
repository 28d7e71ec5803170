// The command line: help, version, usage errors and `rigidity materials` (docs/cli.md).
#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "../output/mini_json.hpp"
#include "run_cli.hpp"

namespace rigidity::testing {
namespace {

TEST_F(CliTest, HelpListsTheCommandsAndExitsZero) {
  const CliOutcome r = rigidity("--help");
  EXPECT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "usage"));
  for (const char* command :
       {"rigidity run", "rigidity validate", "rigidity materials", "rigidity compare", "rigidity plot"})
    EXPECT_TRUE(contains(r.out, command)) << command;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_F(CliTest, EachCommandHasItsHelp) {
  for (const char* command : {"run", "validate", "materials"}) {
    const CliOutcome r = rigidity(std::string(command) + " --help");
    EXPECT_EQ(r.exit_status, 0) << command << ": " << r.err;
    EXPECT_TRUE(contains(r.out, std::string("usage: rigidity ") + command));
  }
  EXPECT_TRUE(contains(rigidity("run -h").out, "--out DIR"));
  EXPECT_TRUE(contains(rigidity("help materials").out, "usage: rigidity materials"));
}

TEST_F(CliTest, VersionIsPrinted) {
  const CliOutcome r = rigidity("--version");
  EXPECT_EQ(r.exit_status, 0);
  EXPECT_EQ(r.out.rfind("rigidity ", 0), 0u) << r.out;
  EXPECT_TRUE(std::any_of(r.out.begin(), r.out.end(), [](char c) { return c >= '0' && c <= '9'; })) << r.out;
}

TEST_F(CliTest, NoCommandIsAUsageError) {
  const CliOutcome r = rigidity("");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "usage"));
  EXPECT_TRUE(r.out.empty());
}

TEST_F(CliTest, UnknownCommandExitsTwoWithTheClosestMatch) {
  CliOutcome r = rigidity("rn scene.yaml");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "unknown command 'rn'"));
  EXPECT_TRUE(contains(r.err, "did you mean 'run'"));
  EXPECT_TRUE(contains(r.err, "usage"));
  EXPECT_TRUE(r.out.empty());

  r = rigidity("materails");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "did you mean 'materials'"));

  r = rigidity("compre");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "did you mean 'compare'"));
}

TEST_F(CliTest, UnknownOptionExitsTwoWithTheClosestMatch) {
  CliOutcome r = rigidity("run --ot somewhere");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "unknown option '--ot'"));
  EXPECT_TRUE(contains(r.err, "did you mean '--out'"));
  EXPECT_TRUE(contains(r.err, "usage: rigidity run"));

  r = rigidity("materials --jsn");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "did you mean '--json'"));

  r = rigidity("--verison");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "did you mean '--version'"));
}

TEST_F(CliTest, MalformedOptionsExitTwo) {
  EXPECT_EQ(rigidity("run --out").exit_status, 2);              // missing value
  EXPECT_EQ(rigidity("run --out a --out b").exit_status, 2);    // given twice
  EXPECT_EQ(rigidity("materials --json=yes").exit_status, 2);   // a flag with a value
  EXPECT_EQ(rigidity("run --set velocity").exit_status, 2);     // not key=value
  EXPECT_EQ(rigidity("run a.yaml b.yaml").exit_status, 2);      // two scenes
  EXPECT_EQ(rigidity("materials rigid hooke").exit_status, 2);  // two names
  EXPECT_TRUE(contains(rigidity("run --set velocity").err, "key.path=value"));
}

// ---- rigidity materials ------------------------------------------------------------

const std::set<std::string> kBuiltInMaterials = {"constant_sound_speed", "formula",  "hooke", "rigid",
                                                 "rigid_fluid",          "tabulated"};

TEST_F(CliTest, MaterialsJsonListsTheBuiltInMaterials) {
  const CliOutcome r = rigidity("materials --json");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const mini_json::Value doc = mini_json::parse(r.out);
  ASSERT_EQ(doc.type, mini_json::Value::Type::array);
  std::set<std::string> names;
  for (const mini_json::Value& material : doc.array) {
    names.insert(material["name"].string);
    EXPECT_EQ(material.keys(), (std::vector<std::string>{"name", "doc", "parameters", "registered_at"}));
    EXPECT_FALSE(material["doc"].string.empty()) << material["name"].string;
    EXPECT_NE(material["registered_at"].string.find(".cpp:"), std::string::npos) << material["registered_at"].string;
    // Built-ins name their file in the source tree, not the path of the machine that built them.
    EXPECT_EQ(material["registered_at"].string.rfind("materials/", 0), 0u) << material["registered_at"].string;
    bool has_rest_density = false;
    for (const mini_json::Value& p : material["parameters"].array) {
      EXPECT_EQ(p.keys(), (std::vector<std::string>{"name", "type", "required", "default", "dimension", "units_natural",
                                                    "units_si", "range", "doc"}));
      EXPECT_EQ(p["required"].boolean, p["default"].type == mini_json::Value::Type::null) << p["name"].string;
      if (p["name"].string == "rest_density") {
        has_rest_density = true;
        EXPECT_EQ(p["default"].number, 1.0);
        EXPECT_EQ(p["units_si"].string, "kg/m^3");
      }
    }
    EXPECT_TRUE(has_rest_density) << material["name"].string;
  }
  EXPECT_EQ(names, kBuiltInMaterials);
}

TEST_F(CliTest, MaterialsListsEveryMaterialAsText) {
  const CliOutcome r = rigidity("materials");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  for (const std::string& name : kBuiltInMaterials) EXPECT_TRUE(contains(r.out, name));
  EXPECT_TRUE(contains(r.out, "rest_density"));
  EXPECT_TRUE(contains(r.out, "registered at"));
}

TEST_F(CliTest, MaterialsHookeShowsItsWaveSpeed) {
  const CliOutcome r = rigidity("materials hooke");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("hooke\n", 0), 0u) << r.out;
  EXPECT_TRUE(contains(r.out, "wave_speed"));
  EXPECT_TRUE(contains(r.out, "required"));
  EXPECT_TRUE(contains(r.out, "m/s"));  // its SI unit
  EXPECT_TRUE(contains(r.out, "(0, 1]"));

  const CliOutcome json = rigidity("materials hooke --json");
  ASSERT_EQ(json.exit_status, 0) << json.err;
  const mini_json::Value doc = mini_json::parse(json.out);
  ASSERT_EQ(doc.array.size(), 1u);
  bool found = false;
  for (const mini_json::Value& p : doc[0]["parameters"].array) {
    if (p["name"].string != "wave_speed") continue;
    found = true;
    EXPECT_TRUE(p["required"].boolean);
    EXPECT_EQ(p["dimension"].string, "velocity");
    EXPECT_EQ(p["units_natural"].string, "c");
    EXPECT_EQ(p["units_si"].string, "m/s");
  }
  EXPECT_TRUE(found);
}

TEST_F(CliTest, UnknownMaterialExitsTwoWithTheClosestMatch) {
  const CliOutcome r = rigidity("materials hoke");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "'hoke'"));
  EXPECT_TRUE(contains(r.err, "did you mean 'hooke'"));
  EXPECT_TRUE(r.out.empty());
}

TEST_F(CliTest, SchemaListsEveryKeyFromTheOneDeclaration) {
  const CliOutcome text = rigidity("schema");
  ASSERT_EQ(text.exit_status, 0) << text.err;
  for (const char* key : {"name:", "materials:", "bodies:", "boundaries:", "solver:", "time:", "outputs:", "tolerance:",
                          "wave_speed:", "# with model: hooke"})
    EXPECT_TRUE(contains(text.out, key)) << key;
  const CliOutcome json = rigidity("schema --json");
  ASSERT_EQ(json.exit_status, 0) << json.err;
  const mini_json::Value doc = mini_json::parse(json.out);
  std::map<std::string, const mini_json::Value*> rows;
  for (const mini_json::Value& row : doc["keys"].array) rows[row["path"].string] = &row;
  ASSERT_TRUE(rows.count("bodies.*.velocity"));
  EXPECT_EQ((*rows["bodies.*.velocity"])["unit"].string, "c");
  EXPECT_EQ((*rows["bodies.*.velocity"])["range"].string, "(-1, 1)");
  EXPECT_EQ((*rows["bodies.*.velocity"])["default"].string, "0");
  ASSERT_TRUE(rows.count("materials.<name>.wave_speed"));
  EXPECT_EQ((*rows["materials.<name>.wave_speed"])["model"].string, "hooke");
  EXPECT_TRUE((*rows["materials.<name>.wave_speed"])["required"].boolean);
  ASSERT_TRUE(rows.count("time.end"));
  EXPECT_TRUE((*rows["time.end"])["required"].boolean);
  // In SI units the same key reads in m/s.
  const mini_json::Value si = mini_json::parse(rigidity("schema --json --si").out);
  for (const mini_json::Value& row : si["keys"].array) {
    if (row["path"].string == "bodies.*.velocity") {
      EXPECT_EQ(row["unit"].string, "m/s");
    }
  }
}

TEST_F(CliTest, PrintSceneShowsTheSceneAsItWouldRunAndRunsNothing) {
  const CliOutcome r = rigidity("run --print-scene --set bodies.0.velocity=0.8 --out never");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "name: paper_wall_impact"));
  EXPECT_TRUE(contains(r.out, "velocity: 0.8"));
  EXPECT_FALSE(fs::exists(dir() / "never"));
  // What it prints is a scene that validates as it stands.
  write_file("printed.yaml", r.out);
  const CliOutcome v = rigidity("validate printed.yaml");
  EXPECT_EQ(v.exit_status, 0) << v.err;
}

TEST_F(CliTest, ASetThatShortensTheRunDropsLaterSnapshotTimesWithANote) {
  // The default scene snapshots at 0.25, 0.5 and 0.75; ending at 0.3 keeps 0.25 only.
  const CliOutcome r = rigidity("run --set time.end=0.3 --out short");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "note: outputs.snapshots.0: times 0.5, 0.75 dropped")) << r.err;
  const std::string snapshots = read_text(dir() / "short" / "snapshots.csv");
  EXPECT_TRUE(contains(snapshots, "\n0.25,"));
  EXPECT_FALSE(contains(snapshots, "\n0.5,"));
  EXPECT_TRUE(contains(read_text(dir() / "short" / "resolved_scene.yaml"), "times: [0.25]"));
  // Ending before every snapshot drops the snapshot; the scene file itself asking for a
  // time beyond its end stays an error.
  const CliOutcome none = rigidity("run --set time.end=0.1 --out shorter");
  ASSERT_EQ(none.exit_status, 0) << none.err;
  EXPECT_TRUE(contains(none.err, "outputs.snapshots.0 dropped"));
  EXPECT_FALSE(fs::exists(dir() / "shorter" / "snapshots.csv"));
  write_file("late.yaml",
             "name: late\nmaterials: {m: {model: rigid}}\nbodies: [{name: b, material: m, length: 1}]\n"
             "time: {end: 1}\noutputs: {snapshots: [{times: [2], quantities: [p]}]}\n");
  const CliOutcome late = rigidity("run late.yaml --out late");
  EXPECT_EQ(late.exit_status, 2);
  EXPECT_TRUE(contains(late.err, "late.yaml:5:32: error: key 'outputs.snapshots.0.times.0'")) << late.err;
}

TEST_F(CliTest, ASetOfTheEndRunsScenesWithoutSnapshotsOrOutputs) {
  // Nothing to clip: a scene with no outputs, and one with probes only, run to the new end.
  write_file("bare.yaml",
             "name: bare\nmaterials: {m: {model: rigid}}\n"
             "bodies: [{name: b, material: m, length: 1, velocity: 0.6}]\n"
             "boundaries: {right: {type: wall, position: 0.8}}\ntime: {end: 1.5}\n");
  const CliOutcome bare = rigidity("run bare.yaml --set time.end=3 --out bare");
  ASSERT_EQ(bare.exit_status, 0) << bare.err;
  EXPECT_TRUE(contains(read_text(dir() / "bare" / "resolved_scene.yaml"), "end: 3")) << bare.out;
  write_file("probed.yaml", read_text(dir() / "bare.yaml") +
                                "outputs: {probes: [{name: w, body: b, at: right, quantities: [p], every: 0.5}]}\n");
  const CliOutcome probed = rigidity("run probed.yaml --set time.end=1 --out probed");
  ASSERT_EQ(probed.exit_status, 0) << probed.err;
}

TEST_F(CliTest, TheDefaultToleranceRunsAGenuinelyNonlinearBarClean) {
  // The paper's scene with a constant_sound_speed bar: a shock, then a fan from the free end
  // that nothing reaches before the end. The fan is held whole and sampled exactly, so the
  // default tolerance and 1e-12 asked for explicitly run alike: no warning, a bound of 0.
  const std::string gas =
      "run --set materials.rigid_steel.model=constant_sound_speed --set materials.rigid_steel.sound_speed=0.5 "
      "--set bodies.0.velocity=0.3 ";
  const CliOutcome quiet_default = rigidity(gas + "--out gas");
  ASSERT_EQ(quiet_default.exit_status, 0) << quiet_default.err;
  EXPECT_FALSE(contains(quiet_default.err, "warning")) << quiet_default.err;
  const CliOutcome asked = rigidity(gas + "--set solver.tolerance=1e-12 --out gas_asked");
  ASSERT_EQ(asked.exit_status, 0) << asked.err;
  EXPECT_FALSE(contains(asked.err, "warning")) << asked.err;
  EXPECT_EQ(read_text(dir() / "gas" / "snapshots.csv"), read_text(dir() / "gas_asked" / "snapshots.csv"));
}

}  // namespace
}  // namespace rigidity::testing
