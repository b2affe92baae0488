#pragma once
// Every key a scene file may contain, declared once (see scene_schema.cpp).
#include "cases/scene/schema.hpp"

namespace hvi::scene {

const TableSpec& scene_schema();

}  // namespace hvi::scene
