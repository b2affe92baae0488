// The material library holds the paper's Tables 1 and 4 exactly: every parameter is compared
// with a copy of the tables (data/paper_materials.csv) in SI.
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <gtest/gtest.h>

#include "mpm/materials/library.hpp"

namespace hvi::mpm {
namespace {

std::vector<std::map<std::string, std::string>> read_table() {
  std::ifstream in(std::string(HVI_SOURCE_DIR) + "/tests/mpm/materials/data/paper_materials.csv");
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (line.back() == ',') cells.emplace_back();
    if (header.empty()) {
      header = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size(); ++k)
      row[header[k]] = k < cells.size() ? cells[k] : "";
    rows.push_back(row);
  }
  return rows;
}

std::optional<double> value(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto& s = row.at(key);
  if (s.empty()) return std::nullopt;
  return std::stod(s);
}

TEST(Library, HoldsThePapersTablesOneAndFour) {
  const auto rows = read_table();
  ASSERT_EQ(rows.size(), 5u);
  for (const auto& row : rows) {
    const std::string name = row.at("name");
    SCOPED_TRACE(name);
    const LibraryMaterial* m = find_library_material(name);
    ASSERT_NE(m, nullptr);
    const HydroModels& p = m->parameters;
    // Units of the table: c0 m/s; rho g/cm^3; E GPa; A, B, sigma_max MPa; T K; cv J/(kg K).
    EXPECT_DOUBLE_EQ(p.density, *value(row, "rho") * 1e3);
    EXPECT_DOUBLE_EQ(p.youngs_modulus, *value(row, "E") * 1e9);
    EXPECT_DOUBLE_EQ(p.poisson_ratio, *value(row, "poisson"));
    EXPECT_DOUBLE_EQ(p.eos_as<MieGruneisen>()->c0, *value(row, "c0"));
    EXPECT_DOUBLE_EQ(p.eos_as<MieGruneisen>()->s, *value(row, "s"));
    EXPECT_DOUBLE_EQ(p.eos_as<MieGruneisen>()->gamma0, *value(row, "gamma0"));
    EXPECT_DOUBLE_EQ(p.eos_as<MieGruneisen>()->reference_density, p.density);
    EXPECT_DOUBLE_EQ(p.johnson_cook->A, *value(row, "A") * 1e6);
    EXPECT_DOUBLE_EQ(p.johnson_cook->B, *value(row, "B") * 1e6);
    EXPECT_DOUBLE_EQ(p.johnson_cook->n, *value(row, "n"));
    EXPECT_DOUBLE_EQ(p.johnson_cook->C, *value(row, "C"));
    EXPECT_DOUBLE_EQ(p.johnson_cook->m, *value(row, "m"));
    EXPECT_DOUBLE_EQ(p.johnson_cook->melt_temperature, *value(row, "T_melt"));
    EXPECT_DOUBLE_EQ(p.johnson_cook->room_temperature, *value(row, "T_room"));
    EXPECT_DOUBLE_EQ(*m->specific_heat, *value(row, "cv"));
    if (auto d1 = value(row, "D1")) {
      ASSERT_TRUE(p.damage.has_value());
      EXPECT_DOUBLE_EQ(p.damage->D1, *d1);
      EXPECT_DOUBLE_EQ(p.damage->D2, *value(row, "D2"));
      EXPECT_DOUBLE_EQ(p.damage->D3, *value(row, "D3"));
      EXPECT_DOUBLE_EQ(p.damage->D4, *value(row, "D4"));
      EXPECT_DOUBLE_EQ(p.damage->D5, *value(row, "D5"));
    } else {
      EXPECT_FALSE(p.damage.has_value());
    }
    if (auto smax = value(row, "sigma_max"))
      EXPECT_DOUBLE_EQ(*p.max_principal_stress, *smax * 1e6);
    else
      EXPECT_FALSE(p.max_principal_stress.has_value());
  }
  // Plus the verification metals.
  for (const char* extra : {"OFHC-Cu", "4340-steel", "42CrMo4"})
    EXPECT_NE(find_library_material(extra), nullptr) << extra;
}

}  // namespace
}  // namespace hvi::mpm
