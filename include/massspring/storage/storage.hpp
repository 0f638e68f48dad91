#pragma once
/// @file
/// @brief All storage policies: Dense and Sparse.

#include "massspring/storage/dense.hpp"
#include "massspring/storage/sparse.hpp"
#include "massspring/storage/tags.hpp"
