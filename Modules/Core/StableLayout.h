#ifndef vimlop_StableLayout_h
#define vimlop_StableLayout_h

/**
 * @file StableLayout.h
 * @brief Fixed-size Eigen types for the members of public structs.
 *
 * Eigen aligns a fixed-size matrix of 32 bytes or more (Matrix2d, Vector4d,
 * Matrix4d, Quaterniond) to the widest SIMD register the compiler targets:
 * 16 bytes by default on x86-64, 32 with -mavx. A struct holding one then has
 * another size and other member offsets in a program built with -mavx than in
 * the packaged library, and every option the program sets is read from the
 * wrong place (a navigation program saw "min 0.5 > max 2.1e-313"). Members of
 * public structs use these unaligned types instead, so that their layout is
 * the same whatever the flags; Eigen still vectorises the arithmetic with
 * unaligned loads. Local variables and private members may use the aligned
 * types.
 */

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vimlop
{

/// @brief A 2 x 2 matrix of doubles whose alignment does not depend on the compiler's flags.
using Matrix2dUnaligned = Eigen::Matrix<double, 2, 2, Eigen::DontAlign>;

/// @brief A quaternion of doubles whose alignment does not depend on the compiler's flags.
using QuaterniondUnaligned = Eigen::Quaternion<double, Eigen::DontAlign>;

} // namespace vimlop

#endif
