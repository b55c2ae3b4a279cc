// The analytic form factor from a differential area to a polygon: Lambert's contour formula
// (J. H. Lambert, "Photometria", 1760; in the form of Cohen and Wallace, "Radiosity and
// Realistic Image Synthesis", 1993, eq. 4.21, and Baum, Rushmeier and Winget, SIGGRAPH 1989):
//   F(x -> P) = (1/2pi) sum_i  n . (R_i x R_{i+1}) / |R_i x R_{i+1}|  gamma_i,
// R_i = p_i - x the vectors to the polygon's vertices, gamma_i the angle between R_i and
// R_{i+1}. It equals int_P cos(theta) cos(theta') / (pi r^2) dA' when all of P lies in front
// of both the point's plane and P's own (one-sided) plane. The clamped cosines of docs/design.md
// are honoured exactly: the polygon is first clipped to the half-space in front of the
// point's plane (points behind contribute zero), and a point behind the source's plane sees
// nothing of it.
#pragma once

#include <Eigen/Core>

#include "kernel/patch.h"

namespace radquad {

// int_{source} max(0,cos theta) max(0,cos theta') / (pi r^2) dA' at the point x with unit
// normal n (no visibility).
double pointToPatchFormFactor(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                              const Patch& source);

}  // namespace radquad
