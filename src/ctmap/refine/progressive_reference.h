#pragma once
/// \file progressive_reference.h
/// The progressive reference of the distortion optimiser (refine/isometric.h, beyond paper §2.4;
/// Liu, Zhuang, Chen, Ling and Zhou 2018, "Progressive parameterizations"): a face whose map is
/// very distorted is measured, for a while, against a reference triangle between its 3D triangle
/// and its UV triangle, chosen so that the map's distortion with respect to it is bounded. The
/// Newton steps on such an energy are long (its Hessian is well conditioned) and move every face
/// towards its 3D shape; as the map improves the references become the 3D triangles.
#include "ctmap/face_jacobian.h"

namespace ctmap {

/// The frame of the reference triangle for a face with frame `F` (its 3D triangle) whose map has
/// the Jacobian `J` with respect to F. With J = U diag(s1, s2) V^T: the reference is the 3D
/// triangle stretched by R = V diag(s1^w, s2^w) V^T, so that the map from it has the singular
/// values s^(1-w), with the smallest w in [0, 1] at which its symmetric Dirichlet density / 4 is
/// at most `bound` (w = 0, F itself, when the face is already within it). The returned frame keeps
/// F's area (the energy's weights stay the 3D areas) and F's handedness.
/// \pre det J > 0; bound > 1.
FaceFrame progressive_frame(const FaceFrame& F, const Mat2& J, double bound);

}  // namespace ctmap
