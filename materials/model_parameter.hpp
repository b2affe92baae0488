#pragma once
// A model's parameter as a scene names it: the key of its table, its SI unit, the bound its value
// must keep, and what it is. The scene layer builds the parameter table and its checks from these;
// the law itself never sees a scene.
namespace hvi::materials {

struct ModelParameter {
  enum class Bound { any, non_negative, positive };
  const char* key;
  const char* si_unit;  // "" for a dimensionless number, else "m/s", "Pa", ...
  Bound bound;
  const char* doc;
};

}  // namespace hvi::materials
