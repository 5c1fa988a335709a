!> The model the legacy program solves, beside its mesh (visco2d_mesh) and
!> materials (visco2d_material): the analysis settings (geometry, element
!> formulation, solver), the supports and loads with their time histories,
!> the probes, the time stages, and where the model was read from (for
!> located errors). visco2d_deck reads a deck into these records; the base
!> (src/base/) computes with them and knows nothing of the cards.
module visco2d_model
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, geometry_axisymmetric, formulation_standard, kinematics_small
  use visco2d_curve, only: curve_t
  use visco2d_mesh, only: edge_set_none
  implicit none
  private

  public :: settings_t, fix_t, pressure_t, force_t, loads_t, probe_t, time_stage_t, source_t
  public :: stage_total_steps

  !> The analysis settings the element and the solver need.
  type :: settings_t
    integer :: geometry = geometry_axisymmetric   !< geometry_axisymmetric or geometry_plane_strain
    integer :: formulation = formulation_standard !< formulation_standard or formulation_bbar
    integer :: solver = 0                         !< the SOLVER card's choice (visco2d_factor's numbers; 0: the default)
    integer :: increments = 10                    !< INCREMENTS= of ANALYSIS STATIC: load increments of a plastic solve
    integer :: iterations = 30                    !< ITERATIONS= of ANALYSIS STATIC: Newton iterations allowed per increment
    logical :: full_newton = .false.              !< NEWTON=FULL of ANALYSIS DYNAMIC: the consistent tangent factored each iteration
    integer :: kinematics = kinematics_small      !< KINEMATICS SMALL | LARGE
  end type settings_t

  !> A support: components prescribed at a set of nodes, u = value * curve(t)
  !> (value 0, no curve: a fixed support).
  type :: fix_t
    integer, allocatable :: nodes(:)
    logical :: fix_r = .false., fix_z = .false.
    real(dp) :: value(2) = 0.0_dp  !< prescribed (u_r, u_z), m
    integer :: curve = 0           !< index into loads%curves; 0 = constant
    integer :: line = 0
  end type fix_t

  !> A uniform normal pressure on a boundary edge set (positive = compressive), p * curve(t).
  type :: pressure_t
    integer :: edge_set = edge_set_none
    real(dp) :: value = 0.0_dp     !< Pa
    integer :: curve = 0           !< index into loads%curves; 0 = constant
    integer :: line = 0
  end type pressure_t

  !> A point load at a node (per radian in axisymmetry), N, times curve(t).
  type :: force_t
    integer :: node = 0
    real(dp) :: value(2) = 0.0_dp
    integer :: curve = 0           !< index into loads%curves; 0 = constant
    integer :: line = 0
  end type force_t

  !> The supports and loads of a model: FIX, PRESSURE, FORCE with their
  !> CURVE time histories, and the body force of gravity.
  type :: loads_t
    type(fix_t), allocatable :: fixes(:)
    type(pressure_t), allocatable :: pressures(:)
    type(force_t), allocatable :: forces(:)
    type(curve_t), allocatable :: curves(:)
    real(dp) :: gravity = 0.0_dp                  !< GRAVITY G=, m/s^2 in -z; 0: no gravity
  end type loads_t

  !> A node whose displacement and stress are reported in the summary and history;
  !> with RADIUS= also a sensor: the mass-weighted mean acceleration of the
  !> nodes within the radius (the rigid-body acceleration of that region).
  type :: probe_t
    character(:), allocatable :: name
    integer :: node = 0
    real(dp) :: radius = 0.0_dp           !< m, RADIUS=; 0: no sensor
    integer, allocatable :: region(:)     !< the sensor's nodes (radius > 0): within radius of the probe point
  end type probe_t

  !> A stage of the time axis: constant steps dt from the previous stage's end to end_time.
  type :: time_stage_t
    real(dp) :: dt = 0.0_dp        !< s (as used: (end - start)/steps)
    real(dp) :: end_time = 0.0_dp  !< s
    integer :: steps = 0
    integer :: line = 0
  end type time_stage_t

  !> Where a model was read from, for the located errors of a failed solve
  !> (visco2d_solve_errors): the input file, and the line and keyword of
  !> each of its cards, in line order.
  type :: source_t
    character(:), allocatable :: file
    integer, allocatable :: lines(:)
    character(len=32), allocatable :: keywords(:)
  end type source_t

contains

  !> Total number of time steps of the stages (each at most visco2d_time's
  !> max_steps; summed in 64 bits all the same).
  pure integer function stage_total_steps(stages) result(total)
    type(time_stage_t), intent(in) :: stages(:)
    integer(int64) :: steps
    integer :: k
    steps = 0
    do k = 1, size(stages)
      steps = steps + int(stages(k)%steps, int64)
    end do
    total = int(min(steps, int(huge(total), int64)))
  end function stage_total_steps
end module visco2d_model
