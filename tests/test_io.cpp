#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "spp/generators.hpp"
#include "spp/io.hpp"

using namespace spp;
namespace fs = std::filesystem;

namespace {
fs::path tmpdir() {
  fs::path d = fs::temp_directory_path() / ("spp_test_io_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
void write(const fs::path& p, const std::string& s) {
  std::ofstream(p) << s;
}
}  // namespace

TEST(Io, SystemJsonRoundTrip) {
  const System s = rod_with_slip(-0.25, 0.25);
  const fs::path p = tmpdir() / "rod.json";
  write_file_atomic(p.string(), system_to_json(s).dump());
  const System t = load_system(p.string());
  EXPECT_EQ((s.M() - t.M()).norm(), 0.0);
  EXPECT_EQ((s.K() - t.K()).norm(), 0.0);
  EXPECT_EQ((s.w() - t.w()).norm(), 0.0);
  EXPECT_EQ(s.g0(), t.g0());
}

TEST(Io, MatrixMarketCoordinateSymmetricAndArray) {
  const fs::path d = tmpdir();
  write(d / "K.mtx", "%%MatrixMarket matrix coordinate real symmetric\n% chain\n2 2 3\n1 1 2\n2 1 -1\n2 2 1\n");
  write(d / "M.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n0\n0\n1\n");
  write(d / "sys.json",
        R"({"name": "mm", "M": {"matrix_market": "M.mtx"}, "K": {"matrix_market": "K.mtx"}, "w": [0, -1], "g0": 1})");
  const System s = load_system((d / "sys.json").string());
  EXPECT_EQ(s.K()(0, 1), -1.0);
  EXPECT_EQ(s.K()(1, 0), -1.0);
  EXPECT_EQ(s.K()(0, 0), 2.0);
  EXPECT_EQ(s.M()(1, 1), 1.0);
}

TEST(Io, ErrorsNameTheFieldAndFile) {
  const fs::path d = tmpdir();
  auto expect = [&](const std::string& json, const std::string& part) {
    write(d / "bad.json", json);
    try {
      load_system((d / "bad.json").string());
      FAIL() << "no error for " << json;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
  };
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1]})", "missing field \"g0\"");
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1)", "malformed JSON");
  expect(R"({"M": [[1,0],[0]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})", "\"M\" row 1 must have 2 entries");
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,"x"],[-1,1]], "w": [0,-1], "g0": 1})", "\"K\"[0][1] must be a number");
  expect(R"({"M": [[1,0],[0,1]], "K": {"matrix_market": "nope.mtx"}, "w": [0,-1], "g0": 1})", "nope.mtx");
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,0], "g0": 1})", "w must be non-zero");
}

TEST(Io, AtomicWriteLeavesNoFileOnFailure) {
  EXPECT_THROW(write_file_atomic("/nonexistent_dir_spp/x.json", "{}"), std::invalid_argument);
  EXPECT_FALSE(fs::exists("/nonexistent_dir_spp/x.json"));
}
