// Configuration (docs/model.md §9): defaults, overrides, and one-line errors that name the key and value.
#include "rotbeam/config.hpp"

#include <fstream>
#include <gtest/gtest.h>

using namespace rotbeam;

namespace {
std::string error_of(const std::string& toml, const std::vector<std::string>& sets = {}) {
  try {
    load_config_string(toml, sets);
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "error must be one line: " << msg;
    return msg;
  }
  ADD_FAILURE() << "no error for: " << toml;
  return {};
}
}  // namespace

TEST(Config, DefaultsAreTheThesisBaseCase) {
  const Config c = load_config_string("", {});
  EXPECT_EQ(c.beam.length_m, 0.0635);
  EXPECT_EQ(c.beam.hub_radius_m, 0.0635);
  EXPECT_EQ(c.beam.diameter_m, 5.08e-4);
  EXPECT_EQ(c.beam.density_kg_m3, 7800.0);
  EXPECT_EQ(c.beam.youngs_modulus_pa, 2.2e11);
  EXPECT_EQ(c.beam.speed_rpm, 550.0);
  EXPECT_EQ(c.surface.depth_fraction, 0.02);
  EXPECT_EQ(c.contact.friction.mu, 0.4);
  EXPECT_EQ(c.beam.modes, 5);
  EXPECT_EQ(c.initial.start, "rigid");
  EXPECT_EQ(c.simulation.scheme, Scheme::adaptive);
  EXPECT_EQ(c.contact.impact.plastic_below_m_s, 0.063);
  EXPECT_EQ(c.simulation.end_angle_deg, 90.0);
  EXPECT_EQ(c.contact.impact.model, RestitutionModel::yigit);
  EXPECT_EQ(c.contact.impact.cap, 1.0);
  EXPECT_EQ(c.contact.impact.speed, RestitutionSpeed::normal);
  EXPECT_FALSE(c.contact.friction.thesis_forces);
  EXPECT_EQ(c.initial.modal_velocity, std::vector<double>(5, 0.0));
}

TEST(Config, ExampleFileEqualsTheDefaults) {
  const Config file = load_config(std::string(ROTBEAM_SOURCE_DIR) + "/examples/thesis-base.toml", {});
  EXPECT_EQ(file.to_json(), load_config_string("", {}).to_json());
}

TEST(Config, OverridesAreReadAsTomlValues) {
  const Config c = load_config_string("[hub]\nspeed_rpm = 1000\n",
                                      {"hub.speed_rpm=3000", "initial.modal_velocity=[2,0,0,0,0]",
                                       "impact.restitution=0.5", "simulation.scheme=thesis", "beam.modes=5"});
  EXPECT_EQ(c.beam.speed_rpm, 3000.0);
  EXPECT_EQ(c.initial.start, "flexible");  // non-zero modal velocity implies a flexible start
  EXPECT_EQ(c.initial.modal_velocity[0], 2.0);
  EXPECT_EQ(c.contact.impact.model, RestitutionModel::constant);
  EXPECT_EQ(c.contact.impact.constant, 0.5);
  EXPECT_EQ(c.simulation.scheme, Scheme::thesis);  // a bare word is a string
  const Config quoted = load_config_string("", {"simulation.scheme=\"thesis\"", "compat.restitution_speed=full"});
  EXPECT_EQ(quoted.simulation.scheme, Scheme::thesis);
  EXPECT_EQ(quoted.contact.impact.speed, RestitutionSpeed::full);
}

TEST(Config, ErrorsNameTheKeyAndTheValue) {
  struct Bad {
    std::string toml;
    std::vector<std::string> sets;
    std::vector<std::string> must_contain;
  };
  const std::vector<Bad> cases = {
      {"[beam]\nlength_m = -0.1\n", {}, {"beam.length_m", "-0.1"}},
      {"[beam]\nlength_m = nan\n", {}, {"beam.length_m", "nan", "finite"}},
      {"[beam]\ndiameter_m = inf\n", {}, {"beam.diameter_m", "inf"}},
      {"[beam]\nmodes = 0\n", {}, {"beam.modes", "0"}},
      {"[beam]\nmodes = 5.0\n", {}, {"beam.modes", "integer"}},
      {"[beam]\nmodes = 1000\n", {}, {"beam.modes", "1000"}},
      {"[beam]\nlenght_m = 0.1\n", {}, {"beam.lenght_m", "unknown key", "beam.length_m"}},
      {"[hub]\nspeed_rpm = \"fast\"\n", {}, {"hub.speed_rpm", "\"fast\"", "number"}},
      {"[hub]\nspeed_rpm = 0\n", {}, {"hub.speed_rpm", "0"}},
      {"[surface]\ndepth_fraction = 0\n", {}, {"surface.depth_fraction", "0"}},
      {"[surface]\ndepth_fraction = -0.02\n", {}, {"surface.depth_fraction", "-0.02"}},
      {"[surface]\nfriction = -0.4\n", {}, {"surface.friction", "-0.4"}},
      {"[impact]\nrestitution = 1.5\n", {}, {"impact.restitution", "1.5"}},
      {"[impact]\nrestitution = \"newton\"\n", {}, {"impact.restitution", "newton"}},
      {"[initial]\nmodal_velocity = [1, 2]\n", {}, {"initial.modal_velocity", "5 values"}},
      {"[initial]\nstart = \"rigid\"\nmodal_velocity = [1, 0, 0, 0, 0]\n", {}, {"initial.start", "rigid"}},
      {"[simulation]\nend_angle_deg = -95\n", {}, {"simulation.end_angle_deg", "-95"}},
      {"[simulation]\nend_angle_deg = -30\n", {}, {"simulation.end_angle_deg", "after the end angle"}},
      {"[simulation]\nscheme = \"euler\"\n", {}, {"simulation.scheme", "euler", "adaptive"}},
      {"[output]\ninterval_s = -1\n", {}, {"output.interval_s", "-1"}},
      {"[simulation]\ncorrector_max_iterations = 0\n", {}, {"simulation.corrector_max_iterations", "0"}},
      {"[compat]\nthesis_forces = 1\n", {}, {"compat.thesis_forces", "true or false"}},
      {"[nosuch]\nx = 1\n", {}, {"nosuch.x", "unknown key"}},
      {"speed = 3\n", {}, {"speed", "[section]"}},
      {"[beam\n", {}, {"TOML syntax error", "line 1"}},
      {"", {"hub.speed=3000"}, {"hub.speed", "unknown key", "hub.speed_rpm"}},
      {"", {"speed_rpm=3000"}, {"speed_rpm", "section.key"}},
      {"", {"hub.speed_rpm"}, {"hub.speed_rpm", "section.key=value"}},
      {"", {"hub.speed_rpm=fast"}, {"hub.speed_rpm", "\"fast\""}},
  };
  for (const Bad& b : cases) {
    const std::string msg = error_of(b.toml, b.sets);
    for (const std::string& part : b.must_contain)
      EXPECT_NE(msg.find(part), std::string::npos) << "'" << msg << "' lacks '" << part << "'";
  }
}

// A value is one line: a line break could carry a second assignment into the TOML text.
TEST(Config, TheTheoryAndTheSwitchesAreCheckedByName) {
  EXPECT_EQ(error_of("", {"beam.theory=timoshenko"}),
            "beam.theory = \"timoshenko\": must be one of \"foreshortening\", \"elastica\"");
  EXPECT_EQ(error_of("", {"beam.modes=60"}), "beam.modes = 60: must be in 1..40 (1..80 with beam.theory = \"elastica\")");
  EXPECT_EQ(error_of("", {"beam.theory=elastica", "beam.modes=81"}),
            "beam.modes = 81: must be in 1..40 (1..80 with beam.theory = \"elastica\")");
  EXPECT_EQ(load_config_string("", {"beam.theory=elastica", "beam.modes=80", "initial.start=rigid"}).beam.modes, 80);
  EXPECT_EQ(error_of("", {"model.centrifugal=1"}), "model.centrifugal = 1: must be true or false");
  EXPECT_NE(error_of("", {"model.gyroscopic=false"}).find("model.gyroscopic: unknown key"), std::string::npos);
  const std::string limit = error_of("", {"beam.theory=elastica", "simulation.deflection_limit_is_error=true"});
  EXPECT_EQ(limit.rfind("simulation.deflection_limit_is_error = true: ", 0), 0u) << limit;
  const Config c = load_config_string("[model]\ncentrifugal = false\ncoriolis = false\n", {});
  EXPECT_FALSE(c.beam.centrifugal);
  EXPECT_FALSE(c.beam.coriolis);
  EXPECT_EQ(c.beam.theory, BeamTheory::foreshortening);
}

TEST(Config, AnOverrideValueIsOneLine) {
  for (const char* o : {"hub.speed_rpm=3000\nsurface.friction=0.9", "hub.speed_rpm=3000\r", "initial.start=rigid\n"}) {
    try {
      load_config_string("", {o});
      ADD_FAILURE() << o << " was accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("the value holds a line break"), std::string::npos) << e.what();
    }
  }
  // The values API (Python's) says the same; a TOML escape \n inside a string is no line break.
  EXPECT_THROW(load_config_values(std::nullopt, {{"hub.speed_rpm", "3000\nsurface.friction = 0.9"}}), ConfigError);
  EXPECT_EQ(load_config_values(std::nullopt, {{"hub.speed_rpm", "3000"}}).beam.speed_rpm, 3000.0);
}

// A huge value is shown by its beginning and its size: the message stays one short line.
TEST(Config, AHugeValueIsShownShort) {
  std::string values = "[1";
  for (int i = 1; i < 100000; ++i) values += ",1";
  for (const std::string& o : {"initial.modal_velocity=" + values + "]", "initial.start=\"" + std::string(5000, 'a') + "\""}) {
    try {
      load_config_string("", {o});
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_LT(m.size(), 200u) << m.substr(0, 300);
      EXPECT_TRUE(m.find("(100000 values)") != std::string::npos || m.find("(5000 characters)") != std::string::npos) << m;
    }
  }
}

TEST(Config, MissingFileIsNamed) {
  try {
    load_config(std::string("/nonexistent/case.toml"), {});
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/case.toml"), std::string::npos);
  }
}

TEST(Config, ResolvedJsonRoundTripsThroughToml) {
  const Config c = load_config_string("", {"beam.modes=3", "initial.modal_velocity=[0.1,0,0]", "hub.speed_rpm=2000"});
  const nlohmann::json j = c.to_json();
  EXPECT_EQ(j["beam"]["modes"], 3);
  EXPECT_EQ(j["initial"]["start"], "flexible");
  EXPECT_EQ(j["hub"]["speed_rpm"], 2000.0);
  // 33, impact.friction, beam.damping_ratio, simulation.{revolutions, until_steady, steady_tolerance,
  // steady_method, multipliers}, output.{history_revolutions, near_surface_interval_s,
  // near_surface_gap_m, bin_deg}, simulation.{integrating_factor, end_when_clear}, brush.{filaments,
  // rows, row_phase_deg, phase_jitter_deg, length_scatter, diameter_scatter, seed, method,
  // population_tolerance, population_max_runs}, surface.{shape,
  // radius_m, speed_rpm, clearance_m, lobes, lobe_amplitude_m, lobe_law}, beam.theory,
  // model.{centrifugal, coriolis}, contact.{model, tip_radius_m, friction_regularization_m_s,
  // stiffness_factor}, surface.{youngs_modulus_pa, poisson}, beam.poisson, beam.axial,
  // wear.{surface_coefficient, surface_hardness_pa, filament_coefficient, filament_hardness_pa,
  // heat_to_filament, track_width_m, profile_bins}, simulation.jacobian
  EXPECT_EQ(config_keys().size(), 82u);
  // The theory, the axial model and the switches appear where they differ from the thesis's, and read back.
  EXPECT_FALSE(j["beam"].contains("theory"));
  EXPECT_FALSE(j["beam"].contains("axial"));
  EXPECT_FALSE(j.contains("model"));
  const Config e = load_config_string("[beam]\ntheory = \"elastica\"\nmodes = 60\n[model]\ncoriolis = false\n", {});
  const nlohmann::json je = e.to_json();
  EXPECT_EQ(je["beam"]["theory"], "elastica");
  EXPECT_EQ(je["model"]["coriolis"], false);
  EXPECT_EQ(je["model"]["centrifugal"], true);
  EXPECT_EQ(revalidate(e).to_json(), je);
  const Config d = load_config_string("", {"beam.modes=3", "beam.damping_ratio=[0.01,0.02,0.03]"});
  EXPECT_EQ(d.to_json()["beam"]["damping_ratio"], nlohmann::json::parse("[0.01,0.02,0.03]"));
  const Config one = load_config_string("[beam]\ndamping_ratio = 0.02\n", {});
  EXPECT_EQ(one.to_json()["beam"]["damping_ratio"], 0.02);
}
