// Layout files (io/layout_file.hpp, issue 13): what `spp reduce --layout` and the animations' "fe" picture read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include "spp/io.hpp"

using namespace spp;

namespace {
std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("spp_layout_" + name + ".json");
  std::ofstream(path) << text;
  return path.string();
}

void expect_refused(const std::string& text, long n, const std::string& part) {
  try {
    read_fe_layout(write_temp("bad", text), n);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(LayoutFile, RoundTripsAndSamplesEvenly) {
  FeLayout l;
  l.coordinates.resize(10, 2);
  l.directions.resize(10, 2);
  l.basis.resize(10, 3);
  l.model_dofs = 10;
  for (int i = 0; i < 10; ++i) {
    l.dofs.push_back(9 - i);
    l.coordinates.row(i) << 0.1 * i, -1.0 / 3.0;
    l.directions.row(i) << 1.0, i % 2;
    l.basis.row(i) << i, 1e-300, -2.5;
  }
  const FeLayout back = read_fe_layout(write_temp("round", fe_layout_json(l)), 10);
  EXPECT_EQ(back.dofs, l.dofs);
  EXPECT_EQ(back.coordinates, l.coordinates);  // bit for bit
  EXPECT_EQ(back.directions, l.directions);
  EXPECT_EQ(back.basis, l.basis);
  EXPECT_EQ(back.model_dofs, 10);
  const FeLayout s = sample_fe_layout(l, 4);
  EXPECT_EQ(s.dofs, (std::vector<long>{9, 6, 3, 0}));  // rows 0, 3, 6, 9: first and last kept
  EXPECT_EQ(s.basis.rows(), 4);
  EXPECT_EQ(s.basis(3, 0), 9.0);
  EXPECT_EQ(sample_fe_layout(l, 20).dofs, l.dofs);
}

TEST(LayoutFile, BadInputIsRefusedNamingTheField) {
  const std::string ok_tail = R"("coordinates": [[0], [1]], "directions": [[1], [1]]})";
  expect_refused(R"({"dofs": [0, 5], )" + ok_tail, 5, "\"dofs\"[1]: expected a whole number from 0 to 4");
  expect_refused(R"({"dofs": [1, 1], )" + ok_tail, 5, "expected each dof once, got dof 1 again");
  expect_refused(R"({"dofs": [0, 1.5], )" + ok_tail, 5, "\"dofs\"[1]");
  expect_refused(R"({"dofs": [0], )" + ok_tail, 5, "\"coordinates\": expected one row per entry of \"dofs\" (1)");
  expect_refused(R"({"dofs": [0, 1], "coordinates": [[0], [1]], "directions": [[1], [0]]})", 5,
                 "\"directions\"[1]: expected a direction, got zero");
  expect_refused(R"({"dofs": [0, 1], "coordinates": [[0, 0, 0, 0], [1, 0, 0, 0]], "directions": [[1], [1]]})", 5,
                 "expected rows of 1 to 3 numbers, got 4");
  expect_refused(R"({"dofs": [0, 1], "coordinates": [[0, 0], [1, 0]], "directions": [[1], [1]]})", 5,
                 "\"directions\": expected rows of 2 numbers, got 1");
  expect_refused(R"({"dofs": [0, 1], "nodes": 3, )" + ok_tail, 5, "\"nodes\"");
  expect_refused(R"({"dofs": [0, 1], "coordinates": [[0], [1]]})", 5, "missing field \"directions\"");
  expect_refused("[1, 2]", 5, "expected a JSON object");
  // a layout of another model (an attack: a 1000-dof bar's layout went through spp reduce of a 2000-dof one)
  expect_refused(R"({"dofs": [0, 1], "model_dofs": 1000, )" + ok_tail, 2000,
                 "\"model_dofs\": expected the layout of this model of 2000 dofs, got the layout of a model of 1000");
}

// Issue 13: a reduced model's layout carries its fingerprint (spp reduce --layout), so that a layout of another
// reduced model with as many dofs is refused where it is drawn (only the basis' shape was checked). The fingerprint
// survives the system file's round trip (w normalised again when read) and tells two such models apart.
TEST(LayoutFile, FingerprintTellsReducedModelsOfOneSizeApart) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(3, 3), K(3, 3);
  K << 2, -1, 0, -1, 2, -1, 0, -1, 1;
  const System a(M, K, Eigen::Vector3d(0.3, -0.7, 1.9), 0.37, "a");
  Eigen::MatrixXd K2 = K;
  K2(2, 2) = 1.0 + 1e-6;
  const System b(M, K2, Eigen::Vector3d(0.3, -0.7, 1.9), 0.37, "b");
  const System a_read = load_system(write_temp("fp_system", system_json(a)));
  EXPECT_TRUE(same_fingerprint(model_fingerprint(a), model_fingerprint(a_read), a_read));
  EXPECT_FALSE(same_fingerprint(model_fingerprint(a), model_fingerprint(b), b));

  FeLayout l;
  l.dofs = {0, 1};
  l.coordinates = Eigen::MatrixXd::Zero(2, 1);
  l.directions = Eigen::MatrixXd::Ones(2, 1);
  l.basis = Eigen::MatrixXd::Ones(2, 3);
  l.model_dofs = 50;
  l.fingerprint = model_fingerprint(a);
  const FeLayout back = read_fe_layout(write_temp("fp", fe_layout_json(l)), -1);  // (the full model's dofs unknown)
  ASSERT_EQ(back.fingerprint.size(), 5);
  EXPECT_EQ(back.fingerprint, l.fingerprint);
  check_fe_layout(back, a_read, "a.layout.json", "a.json");  // its own model, read back: taken
  try {
    check_fe_layout(back, b, "a.layout.json", "b.json");
    ADD_FAILURE() << "a layout of another reduced model was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("a.layout.json is not a layout of b.json: field \"model_fingerprint\""),
              std::string::npos)
        << e.what();
  }
  l.fingerprint.resize(0);  // without one (a hand-written layout): the shape alone
  check_fe_layout(l, b, "l.json", "b.json");
  EXPECT_THROW(
      check_fe_layout(
          l, System(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Identity(2, 2), Eigen::Vector2d(1, 0), 1.0),
          "l.json", "c.json"),
      std::invalid_argument);
}
