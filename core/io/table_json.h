#pragma once
/// @file table_json.h
/// A Table as JSON: an array of objects keyed by column name; non-finite values become null.

#include <nlohmann/json.hpp>

#include "core/common/table.h"

namespace terra::io {

nlohmann::json toJson(const Table& table);

}  // namespace terra::io
