// The scene file's sections (coupling/input/): every entry's default reads back as itself, the
// entries land in the members the old hand-written extraction filled, and no name is declared
// twice (docs/architecture.md, "How to add a section").
#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling {
namespace {

using input::Entry;
using input::Section;

TEST(SceneSections, NamesAreUnique) {
  std::set<std::string> sections;
  for (const Section& s : input::scene_sections()) {
    EXPECT_TRUE(sections.insert(s.name).second) << s.name;
    std::set<std::string> entries;
    for (const Entry& e : s.entries) EXPECT_TRUE(entries.insert(e.name).second) << s.name << "/" << e.name;
    EXPECT_FALSE(s.entries.empty()) << s.name;
  }
}

TEST(SceneSections, RealsWrittenShortestReadBackExactly) {
  for (double v : {1e-6, 5e9, 0.045, 1.5e-3, 2650.0, 0.1, 1.0 / 3.0, 1e10, 1e-12, 0.0, -0.25, 12.5}) {
    const std::string s = input::format_real(v);
    EXPECT_EQ(std::stod(s), v) << s;
    EXPECT_EQ(s.find('+'), std::string::npos) << s;
  }
  EXPECT_EQ(input::format_real(1e-6), "1e-6");
  EXPECT_EQ(input::format_real(5e9), "5e9");
  EXPECT_EQ(input::format_real(0.045), "0.045");
}

// The printed default file, read back, gives every entry the value it was printed from.
TEST(SceneSections, DefaultsSurviveTheParameterFile) {
  std::ostringstream file;
  print_default_parameters(file);
  SceneInput read = parse_scene_text(file.str(), "defaults.prm");
  SceneInput defaults;
  for (const Section& s : input::scene_sections())
    for (const Entry& e : s.entries) EXPECT_EQ(e.write(read), e.write(defaults)) << s.name << "/" << e.name;
}

// The four defaults that once differed between the scene file and the engine's structs.
TEST(SceneSections, EngineDefaultsAreTheSceneFiles) {
  const SceneInput in = parse_scene_text("subsection Output\n  set folder = x\nend\n", "x.prm");
  const dem::SceneConfig plain;
  EXPECT_EQ(in.scene.time_step, plain.time_step);
  EXPECT_EQ(in.scene.end_time, plain.end_time);
  EXPECT_EQ(in.scene.fill.bottom_gap, plain.fill.bottom_gap);
  EXPECT_EQ(in.scene.fill.position_jitter, plain.fill.position_jitter);
}

TEST(SceneSections, EntriesLandInTheirMembers) {
  const SceneInput in = parse_scene_text(
      "subsection Container\n  set length x = 0.05\n  set wall y max friction = 0.3\n"
      "  set collapse = constrained\nend\n"
      "subsection Particles\n  set gradation = 1e-3:0, 2e-3:1\n  set shapes = 10:8:6@2, 1:0.5:0.5\nend\n"
      "subsection Contact\n  set law = hooke\n  set normal stiffness = 1234\nend\n"
      "subsection Fill\n  set method = random\n  set initial velocity = 0, 0, -1.5\n  set seed = 7\nend\n"
      "subsection Parallel\n  set blocks = 2, 1, 1\n  set balance cost = pair slots\nend\n"
      "subsection Strain\n  set definitions = tessellation\nend\n"
      "subsection CoarseGraining\n  set fields = stress, displacement\nend\n"
      "subsection Stress\n  set formulas = bagi, weber, bagi\nend\n"
      "subsection Lid\n  set target stresses = 100, 200\nend\n"
      "subsection Accuracy\n  set grids = 1 2 3; 4 5 6\n  set fem degrees = 2\nend\n"
      "subsection Effects\n  set rotation = false\nend\n",
      "x.prm");
  EXPECT_EQ(in.scene.container.lx, 0.05);
  EXPECT_EQ(in.scene.container.friction[4], 0.3);
  EXPECT_EQ(in.scene.container.friction[3], 0.5);
  EXPECT_EQ(in.collapse, "constrained");
  ASSERT_EQ(in.scene.particles.gradation.size(), 2u);
  EXPECT_EQ(in.scene.particles.gradation[1].radius, 2e-3);
  ASSERT_EQ(in.scene.particles.shapes.size(), 2u);
  EXPECT_DOUBLE_EQ(in.scene.particles.shapes[0].ratios[0], 0.8);
  EXPECT_EQ(in.scene.particles.shapes[0].number_fraction, 2.0);
  EXPECT_EQ(in.scene.contact_law, "hooke");
  bool stiffness = false;
  for (const dem::NamedValue& v : in.scene.law_parameters)
    if (v.name == "normal stiffness") stiffness = v.value == 1234.0;
  EXPECT_TRUE(stiffness);
  EXPECT_EQ(in.scene.fill.method, dem::FillMethod::random);
  EXPECT_EQ(in.scene.fill.velocity.z(), -1.5);
  EXPECT_EQ(in.scene.fill.seed, 7u);
  EXPECT_EQ(in.parallel.blocks[0], 2);
  EXPECT_TRUE(in.parallel.balance_by_pairs);
  EXPECT_FALSE(in.output.grid_strain.kernel.definitions[0]);
  EXPECT_TRUE(in.output.grid_strain.kernel.definitions[1]);
  const CoarseGrainingOptions& cg = in.study.coarse_graining;
  EXPECT_TRUE(cg.stress && cg.displacement);
  EXPECT_FALSE(cg.density || cg.velocity || cg.wall_force_density || cg.momentum_balance);
  ASSERT_EQ(in.output.grid_stress.formulas.size(), 2u);  // repeats kept once, in the file's order
  EXPECT_EQ(in.output.grid_stress.formulas[0], dem::StressFormula::bagi);
  EXPECT_EQ(in.control.lid.target_stresses, (std::vector<double>{100, 200}));
  ASSERT_EQ(in.accuracy.grids.size(), 2u);
  EXPECT_EQ(in.accuracy.grids[1][2], 6);
  EXPECT_EQ(in.accuracy.fem_degrees, (std::vector<unsigned>{2}));
  EXPECT_EQ(in.effect_switches.rotation, dem::EffectSwitch::off);
  EXPECT_EQ(in.effect_switches.gravity, dem::EffectSwitch::automatic);
}

// A law's parameters are kept only for the scene's own law.
TEST(SceneSections, LawParametersOnlyForTheSceneLaw) {
  const SceneInput in = parse_scene_text("subsection Contact\n  set normal stiffness = 1234\nend\n", "x.prm");
  EXPECT_EQ(in.scene.contact_law, "hertz-mindlin");
  EXPECT_TRUE(in.scene.law_parameters.empty());
}

// A checkpoint keeps defaults as the version that wrote it printed them.
TEST(SceneSections, RestartComparesNumbersByValue) {
  const std::string a = "subsection Particles\n  set radius = 1.5e-3\nend\n";
  const std::string b = "subsection Particles\n  set radius = 0.0015\nend\n";
  const std::string c = "subsection Particles\n  set radius = 0.002\nend\n";
  EXPECT_TRUE(differing_parameters(a, b).empty());
  EXPECT_EQ(differing_parameters(a, c).size(), 1u);
}

}  // namespace
}  // namespace upgrain::coupling
