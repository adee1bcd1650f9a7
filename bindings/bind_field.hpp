// Conversions between NumPy arrays and lidar_overlap::Field (and plain real images), shared by the binding files.
#pragma once

#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "lidar_overlap/fourier/field.hpp"

using ComplexArray =
    pybind11::array_t<std::complex<double>, pybind11::array::c_style | pybind11::array::forcecast>;

lidar_overlap::Field field_from_array(const ComplexArray& values, double spacing,
                                      double wavelength);
ComplexArray array_from_field(const lidar_overlap::Field& f);

// An n x n row-major real image (phase plate, screen, far field) as a NumPy array.
pybind11::array_t<double> square_array(const std::vector<double>& values, std::size_t n);
