!> ANALYSIS STATIC with KINEMATICS LARGE: the equilibrium of a hyperelastic
!> body at finite deformation, the loads (point loads and gravity, dead;
!> prescribed displacements) applied in `settings%increments` equal
!> increments (INCREMENTS=, default 10), each solved by Newton's method
!> with the tangent of visco2d_finite_element (material and stress terms:
!> quadratic convergence).
!>
!> In increment k the load is lambda_k R, lambda_k = k / N, and the
!> prescribed displacements lambda_k u_p. Newton iteration i solves
!> K_t du = lambda_k R - f(u) on the free equations (the prescribed values'
!> increment taken in the first iteration), K_t and f assembled from every
!> element's response at u. A correction that would invert an element is
!> halved (up to 20 times) before it is taken. An increment has converged
!> when both
!>   |r| <= force_tolerance max(|lambda_k R|, |f|)       (free equations)
!>   |r . K_t^-1 r| <= energy_tolerance |du_1 . r_0|     (the energy norm of the next correction)
!> hold, the same tests as the plastic static solve; after ITERATIONS= (default 30) a located error
!> (the ANALYSIS card, the increment, the iteration, both residuals) is returned, never a result.
!>
!> With a PLATE (finite_plate_t, from the driver) the contact is an active
!> set inside each increment: the nodes on the plate at the start are held;
!> after an increment converges, a free candidate that went through the plate
!> is held at z + u_z = Z (STICK: u_r too, where it is), a held node whose
!> reaction would pull the body onto the plate is freed, and the increment's
!> Newton iteration goes on from there with the new set, until the set no
!> longer changes (at most contact_sets times; the keys force_N,
!> contact_nodes, contact_iterations, contact_radius_mm). The plate's
!> condition is on the current height z + u_z: the contact is on the
!> deformed body.
!>
!> The stored energy is the strain energy W integrated over the reference
!> body; the external work the trapezoidal sum over the increments of
!> 1/2 (P_(k-1) + P_k) . (u_k - u_(k-1)), P the applied load on the free
!> equations and the reactions on the supported ones: W - U is the
!> trapezoid's O(1/N^2) error plus the force tolerance.
module visco2d_finite_static
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, whole_body_factor
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, short_real
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: material_t
  use visco2d_model, only: settings_t, loads_t, source_t
  use visco2d_quadrilateral, only: gauss_count
  use visco2d_banded, only: band_matrix_t, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card, solve_failure_text, correction_energy
  use visco2d_assembly, only: external_load, gravity_load, support_mask, prescribed_displacement, &
                              nodal_field, nodal_average
  use visco2d_static, only: static_solution_t
  use visco2d_solve_errors, only: singular_error, not_finite_error, analysis_error
  use visco2d_record, only: record_t, record_put_integer, record_put_real
  use visco2d_finite_assembly, only: finite_assemble, strain_extremes
  implicit none
  private

  public :: finite_summary_t, finite_plate_t, solve_finite_static, finite_record

  !> The rigid plate z = Z of a static run (the PLATE card), as the driver
  !> gives it: its height, STICK or SLIP, the boundary nodes that may touch
  !> it and the distance within which a node is on it.
  type :: finite_plate_t
    real(dp) :: z = 0.0_dp
    logical :: stick = .false.
    integer, allocatable :: candidates(:)
    real(dp) :: tolerance = 0.0_dp
  end type finite_plate_t

  integer, parameter :: contact_sets = 50      !< most changes of the contact set in one load increment

  real(dp), parameter :: force_tolerance = 1.0e-9_dp    !< |r| relative to the load (and reactions)
  real(dp), parameter :: energy_tolerance = 1.0e-18_dp  !< |r . K^-1 r| relative to the first iteration's
  integer, parameter :: halvings = 20                   !< most halvings of a correction that inverts an element

  !> What a finite-deformation static solve adds to the static solution.
  type :: finite_summary_t
    integer :: increments = 0                       !< load increments N
    integer :: iterations = 0                       !< Newton iterations, all increments
    integer :: iterations_max = 0                   !< the most in one increment
    integer :: halvings = 0                         !< corrections halved because they inverted an element
    real(dp), allocatable :: force_residual(:, :)   !< (ITERATIONS, N) |r| / max(|lambda R|, |f|) after each iteration
    real(dp) :: volume_ratio_min = 1.0_dp           !< the least J = det F at a Gauss point
    real(dp) :: volume_ratio_max = 1.0_dp           !< the largest J
    real(dp) :: stretch_min = 1.0_dp                !< the least principal stretch at a Gauss point (in-plane or hoop)
    logical :: plate = .false.                      !< on a PLATE: the keys below
    integer :: contact_nodes = 0                    !< nodes held on the plate at the end
    integer :: contact_iterations = 0               !< increments repeated because the contact set changed
    real(dp) :: plate_force = 0.0_dp                !< the plate's force on the body, N (whole body in axisymmetry)
    real(dp) :: contact_radius = 0.0_dp             !< the current r of the outermost node on the plate, m
  end type finite_summary_t

contains

  !> The load-incremented Newton solve (module comment): the static
  !> solution (displacement, reactions, Cauchy stresses and logarithmic
  !> strains at the Gauss points, stored energy, external work) and the summary.
  subroutine solve_finite_static(mesh, materials, settings, loads, source, solution, summary, error, plate)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    type(source_t), intent(in) :: source
    type(static_solution_t), intent(out) :: solution
    type(finite_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(finite_plate_t), intent(in), optional :: plate   !< a PLATE: contact as an active set (module comment)
    real(dp), allocatable :: load(:), presc(:), u(:), u_start(:), du(:), rhs(:), force(:), force_start(:), r(:)
    real(dp), allocatable :: target(:), stress(:, :, :), strain(:, :, :), held_value(:)
    logical, allocatable :: fixed(:), supports(:), held(:)
    type(band_matrix_t) :: stiffness
    type(factor_t) :: factor
    real(dp) :: lambda, energy_first, energy_next, force_ratio, scale, energy
    integer :: n, k, iteration, info, cut, bad_element, set
    logical :: converged, first, changed

    n = settings%increments
    load = external_load(mesh, settings, loads, 0.0_dp) + gravity_load(mesh, settings, materials, loads)
    supports = support_mask(mesh, settings, loads)
    fixed = supports
    allocate(held(2*mesh%nnode), held_value(2*mesh%nnode))
    held = .false.
    held_value = 0.0_dp
    summary%plate = present(plate)
    presc = prescribed_displacement(mesh, loads, 0.0_dp)
    allocate(u(2*mesh%nnode), stress(4, gauss_count, mesh%nelem), strain(4, gauss_count, mesh%nelem))
    u = 0.0_dp
    lambda = 0.0_dp
    if (present(plate)) call touch_plate(changed, .true.)  ! the nodes that start on it
    summary%increments = n
    allocate(summary%force_residual(settings%iterations, n))
    summary%force_residual = 0.0_dp
    solution%external_work = 0.0_dp
    call evaluate(u, bad_element)                      ! f(0) = 0 and K_t(0), the small-strain stiffness
    if (bad_element > 0) then
      call analysis_error(source, error, &
        'element '//integer_text(mesh%element_id(bad_element))//' is degenerate in the '// &
                          'undeformed mesh')
      return
    end if

    do k = 1, n
      lambda = real(k, dp)/real(n, dp)
      u_start = u
      force_start = force
      do set = 1, contact_sets                         ! the increment, repeated while the contact set changes
      target = merge(held_value, lambda*presc, held)
      energy_first = 0.0_dp
      converged = .false.
      first = .true.
      do iteration = 1, settings%iterations
        rhs = lambda*load - force
        if (first) then
          call band_constrain_rhs(stiffness, fixed, target - u, rhs)
        else
          call band_constrain_rhs(stiffness, fixed, 0.0_dp*u, rhs)
        end if
        call factor_compute(factor, stiffness, fixed, info, solver_of_card(settings%solver))
        if (info > 0) then
          if (k == 1 .and. iteration == 1) then
            call singular_error(mesh, source, info, error)
          else
            call analysis_error(source, error, &
              'the tangent stiffness is singular in load increment '//integer_text(k)//' of '// &
              integer_text(n)//' (Newton iteration '//integer_text(iteration)//', equation '//integer_text(info)// &
              '): the body may have buckled or reached a limit point; give more INCREMENTS=')
          end if
          return
        end if
        du = rhs
        call factor_solve(factor, du, info)
        if (info /= 0) then
          call set_error(error, solve_failure_text(info))     ! located by the driver
          return
        end if
        if (first) energy_first = abs(sum(merge(0.0_dp, du*rhs, fixed)))
        first = .false.
        do cut = 0, halvings                           ! never an inverted element: halve the correction
          call evaluate(u + du, bad_element)
          if (bad_element == 0) exit
          if (cut == halvings) then
            call analysis_error(source, error, &
              'element '//integer_text(mesh%element_id(bad_element))//' inverts in load '// &
              'increment '//integer_text(k)//' of '//integer_text(n)//' (Newton iteration '//integer_text(iteration)// &
              ', the correction halved '//integer_text(halvings)//' times): the deformation is beyond what this '// &
              'mesh can follow, or the increments are too large; give more INCREMENTS=')
            return
          end if
          du = 0.5_dp*du
          summary%halvings = summary%halvings + 1
        end do
        u = u + du
        r = lambda*load - force
        scale = max(norm2(lambda*load), norm2(force), tiny(1.0_dp))
        force_ratio = norm2(merge(0.0_dp, r, fixed))/scale
        summary%force_residual(iteration, k) = force_ratio
        if (.not. (ieee_is_finite(force_ratio) .and. all(ieee_is_finite(u)))) then
          call analysis_error(source, error, &
            'the finite-deformation static solve diverged in load increment '//integer_text(k)// &
            ' of '//integer_text(n)//' (Newton iteration '//integer_text(iteration)//': the displacement or the '// &
            'residual is not finite)')
          return
        end if
        call correction_energy(factor, r, fixed, energy_next, info)   ! the next correction's, with the last factor
        if (info /= 0) then
          call set_error(error, solve_failure_text(info))     ! located by the driver
          return
        end if
        if (force_ratio <= force_tolerance .and. (energy_next <= energy_tolerance*energy_first .or. &
                                                  energy_first == 0.0_dp)) then
          converged = .true.
          exit
        end if
      end do
      if (.not. converged) then
        call analysis_error(source, error, 'the finite-deformation static solve did not converge in load increment '// &
          integer_text(k)//' of '//integer_text(n)//': after '//integer_text(settings%iterations)//' Newton '// &
          'iterations the force residual is '//short_real(force_ratio)//' of the load (tolerance '// &
          short_real(force_tolerance)//') and the energy norm '//short_real(energy_next/max(energy_first, &
          tiny(1.0_dp)))//' of the first iteration''s (tolerance '//short_real(energy_tolerance)//'); give more '// &
          'INCREMENTS= (or ITERATIONS=)')
        return
      end if
      summary%iterations = summary%iterations + iteration
      summary%iterations_max = max(summary%iterations_max, iteration)
      if (.not. present(plate)) exit
      call touch_plate(changed, .false.)
      if (.not. changed) exit
      summary%contact_iterations = summary%contact_iterations + 1
      if (set == contact_sets) then
        call analysis_error(source, error, 'the contact set with the PLATE still changes after '// &
          integer_text(contact_sets)//' repetitions of load increment '//integer_text(k)//' of '//integer_text(n)// &
          ' (KINEMATICS LARGE): give more INCREMENTS=')
        return
      end if
      end do
      solution%external_work = solution%external_work + 0.5_dp*dot_product( &
        merge(force_start, (lambda - 1.0_dp/n)*load, fixed) + merge(force, lambda*load, fixed), u - u_start)
    end do

    if (present(plate)) call plate_keys()
    solution%displacement = nodal_field(mesh, u)
    solution%reaction = nodal_field(mesh, force - load)
    solution%strain = strain
    solution%stress = stress
    solution%nodal_stress = nodal_average(mesh, stress)
    solution%strain_energy = energy
    call strain_extremes(strain, summary%volume_ratio_min, summary%volume_ratio_max, summary%stretch_min)
    if (.not. all(ieee_is_finite(solution%stress)) .or. .not. ieee_is_finite(solution%strain_energy) .or. &
        .not. ieee_is_finite(solution%external_work)) &
      call not_finite_error(source, 'the finite-deformation stress or energy', error)

  contains

    !> The contact set after a converged solve at u: a free candidate that
    !> went through the plate (z + u_z < Z - tolerance) is held at z + u_z = Z
    !> (with STICK also u_r where it is); a held node whose reaction pulls the
    !> body onto the plate (f - lambda R < 0 in z: the plate would pull) is
    !> freed. `fixed`, `held` and `held_value` follow; `changed` if any node moved.
    subroutine touch_plate(changed, initial)
      logical, intent(out) :: changed
      logical, intent(in) :: initial                 !< before the first increment: the nodes within the tolerance
      real(dp) :: gap
      integer :: i, node, rr, zz
      changed = .false.
      do i = 1, size(plate%candidates)
        node = plate%candidates(i)
        rr = 2*mesh%equation(node) - 1
        zz = rr + 1
        if (supports(zz)) cycle
        if (held(zz)) then
          if (force(zz) - lambda*load(zz) < 0.0_dp) then
            held(zz) = .false.
            if (plate%stick .and. .not. supports(rr)) held(rr) = .false.
            changed = .true.
          end if
        else
          gap = mesh%xy(2, node) + u(zz) - plate%z
          if (.not. (gap < -plate%tolerance .or. (initial .and. gap <= plate%tolerance))) cycle
          held(zz) = .true.
          held_value(zz) = plate%z - mesh%xy(2, node)
          if (plate%stick .and. .not. supports(rr)) then
            held(rr) = .true.
            held_value(rr) = u(rr)
          end if
          changed = .true.
        end if
      end do
      fixed = supports .or. held
    end subroutine touch_plate

    !> The plate's keys at the end: the nodes on it, its force on the body
    !> (the held z equations' f - R; whole body in axisymmetry) and the
    !> current radius of the outermost node on it.
    subroutine plate_keys()
      integer :: i, node, zz
      summary%contact_nodes = 0
      summary%plate_force = 0.0_dp
      summary%contact_radius = 0.0_dp
      do i = 1, size(plate%candidates)
        node = plate%candidates(i)
        zz = 2*mesh%equation(node)
        if (.not. held(zz)) cycle
        summary%contact_nodes = summary%contact_nodes + 1
        summary%plate_force = summary%plate_force + force(zz) - load(zz)
        summary%contact_radius = max(summary%contact_radius, abs(mesh%xy(1, node) + u(zz - 1)))
      end do
      summary%plate_force = whole_body_factor(settings%geometry)*summary%plate_force
    end subroutine plate_keys

    !> Every element's response at the displacement v (finite_assemble): the
    !> internal force, the tangent (in `stiffness`), the stresses, strains and
    !> the energy; `bad` the first inverted element (0: none), and then nothing is kept.
    subroutine evaluate(v, bad)
      real(dp), intent(in) :: v(:)
      integer, intent(out) :: bad
      real(dp), allocatable :: trial_force(:), trial_stress(:, :, :), trial_strain(:, :, :)
      type(band_matrix_t) :: trial_stiffness
      real(dp) :: trial_energy
      allocate(trial_force(2*mesh%nnode), trial_stress(4, gauss_count, mesh%nelem), &
               trial_strain(4, gauss_count, mesh%nelem))
      call finite_assemble(mesh, materials, settings, v, trial_force, trial_stress, trial_strain, trial_energy, bad, &
                           trial_stiffness)
      if (bad > 0) return
      call move_alloc(trial_force, force)
      call move_alloc(trial_stress, stress)
      call move_alloc(trial_strain, strain)
      ! A held equation keeps its diagonal in the constrained system (band_constrain_matrix) and the
      ! held value's right-hand side is that diagonal times the value; under a large compression the
      ! stress term can make a held equation's diagonal negative (the free system is still positive
      ! definite), which Cholesky would refuse: its magnitude holds the value as well.
      where (fixed) trial_stiffness%ab(1, :) = abs(trial_stiffness%ab(1, :))
      stiffness = trial_stiffness
      energy = trial_energy
    end subroutine evaluate

  end subroutine solve_finite_static

  !> The summary keys of a finite-deformation static solve (doc/outputs.md).
  subroutine finite_record(summary, record)
    type(finite_summary_t), intent(in) :: summary
    type(record_t), intent(inout) :: record
    call record_put_integer(record, 'load_increments', summary%increments)
    call record_put_integer(record, 'newton_iterations', summary%iterations)
    call record_put_integer(record, 'newton_iterations_max', summary%iterations_max)
    call record_put_integer(record, 'newton_halvings', summary%halvings)
    call record_put_real(record, 'volume_ratio_min', summary%volume_ratio_min)
    call record_put_real(record, 'volume_ratio_max', summary%volume_ratio_max)
    call record_put_real(record, 'stretch_min', summary%stretch_min)
    if (.not. summary%plate) return
    call record_put_real(record, 'force_N', summary%plate_force)
    call record_put_integer(record, 'contact_nodes', summary%contact_nodes)
    call record_put_integer(record, 'contact_iterations', summary%contact_iterations)
    call record_put_real(record, 'contact_radius_mm', 1.0e3_dp*summary%contact_radius)
  end subroutine finite_record
end module visco2d_finite_static
