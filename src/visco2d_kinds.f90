!> Working precision and mathematical constants shared by every module.
module visco2d_kinds
  implicit none
  private

  !> Double precision real kind used throughout visco2d.
  integer, parameter, public :: dp = selected_real_kind(15, 307)
  !> pi to working precision.
  real(dp), parameter, public :: pi = 3.14159265358979323846264338327950288_dp
  !> Relative tolerance for geometric coincidence tests (node on a line, etc.).
  real(dp), parameter, public :: geometry_tolerance = 1.0e-9_dp

  !> Geometry codes.
  integer, parameter, public :: geometry_axisymmetric = 1, geometry_plane_strain = 2

  !> Element formulation codes (FORMULATION card): the legacy fully integrated
  !> element, or B-bar (mean dilatation) against volumetric locking.
  integer, parameter, public :: formulation_standard = 1, formulation_bbar = 2
end module visco2d_kinds
