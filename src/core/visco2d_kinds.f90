!> Working precision and mathematical constants shared by every module.
module visco2d_kinds
  implicit none
  private

  !> Double precision real kind used throughout visco2d.
  integer, parameter, public :: dp = selected_real_kind(15, 307)
  !> pi to working precision.
  real(dp), parameter, public :: pi = 3.14159265358979323846264338327950288_dp
  !> Hertz impact's t_m V / alpha_m (eq. [44]; 0.4 B(0.4, 0.5) = 1.47162; the
  !> paper prints 1.47): here because both the contact reference
  !> (visco2d_hertz) and the progress estimate (core) need it.
  real(dp), parameter, public :: hertz_time_constant = 1.4716_dp
  !> Relative tolerance for geometric coincidence tests (node on a line, etc.).
  real(dp), parameter, public :: geometry_tolerance = 1.0e-9_dp

  !> Geometry codes.
  integer, parameter, public :: geometry_axisymmetric = 1, geometry_plane_strain = 2

  !> Element formulation codes (FORMULATION card): the legacy fully integrated
  !> element, or B-bar (mean dilatation) against volumetric locking.
  integer, parameter, public :: formulation_standard = 1, formulation_bbar = 2

  !> Kinematics codes (KINEMATICS card): small strain (the paper's, the
  !> default) or finite deformation (src/finite/).
  integer, parameter, public :: kinematics_small = 1, kinematics_large = 2

  public :: whole_body_factor, energy_basis

contains

  !> The factor from the solver's integrals (over r dr dz per radian in
  !> axisymmetry, over dx dy per metre of thickness in plane strain) to the
  !> reported energies, masses and reactions: 2 pi in axisymmetry (the whole
  !> body of revolution), 1 in plane strain (per metre of thickness).
  pure real(dp) function whole_body_factor(geometry)
    integer, intent(in) :: geometry  !< geometry_axisymmetric or geometry_plane_strain
    whole_body_factor = 1.0_dp
    if (geometry == geometry_axisymmetric) whole_body_factor = 2.0_dp*pi
  end function whole_body_factor

  !> The summary's energy_basis: what the energy, mass and reaction keys are integrated over.
  pure function energy_basis(geometry) result(basis)
    integer, intent(in) :: geometry  !< geometry_axisymmetric or geometry_plane_strain
    character(len=:), allocatable :: basis
    if (geometry == geometry_axisymmetric) then
      basis = 'whole body'
    else
      basis = 'per metre of thickness'
    end if
  end function energy_basis
end module visco2d_kinds
