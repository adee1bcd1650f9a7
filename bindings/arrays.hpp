// C++ result vectors as NumPy arrays (copies), one conversion for every result property.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <pybind11/numpy.h>

// A 1-D array of v's values: float64 for double, bool for bool (std::vector<bool> has no data()), uint64
// for counts.
template <class T>
pybind11::array_t<T> to_array(const std::vector<T>& v) {
  pybind11::array_t<T> out(static_cast<pybind11::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

// rows[k][j] as a K x N array (rows of equal length; K x 0 when there are none).
inline pybind11::array_t<double> to_array(const std::vector<std::vector<double>>& rows) {
  const std::size_t n = rows.empty() ? 0 : rows.front().size();
  pybind11::array_t<double> out({rows.size(), n});
  for (std::size_t k = 0; k < rows.size(); ++k)
    std::copy(rows[k].begin(), rows[k].end(), out.mutable_data() + k * n);
  return out;
}
