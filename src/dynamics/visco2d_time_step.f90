!> The stages of one time step, each a procedure with explicit arguments, in
!> the order the step runs them (one sub-step per row of the integrator,
!> module visco2d_integrators; Wilson-theta and the Newmark family have one,
!> Bathe two):
!>   effective_stiffness   S~ = (1 - alpha_f) S_h + c M                 eq. [35]
!>   factor_effective      S~ with the supports imposed, factored (visco2d_factor)
!>   effective_load        R~ = R_h - F(sigma_t) - (1 - alpha_f) F(s0_h) + M b   eq. [36]
!>   solve_supports        S~ dU = R~ with the supports only             eq. [34]
!>   contact_repeat        the plate's conditions on dU (capacitance system), the
!>                         update to the sub-step's end (eqs. [37]-[39]) and the
!>                         trial stresses (eqs. [13], [14], [23]), repeated while the
!>                         contact set changes; with a PLASTIC material, or with
!>                         KINEMATICS LARGE (f(U) of the bodies at finite deformation,
!>                         visco2d_finite_force / visco2d_finite_assembly, in place of
!>                         S U), each solve is iterated to equilibrium at the solve
!>                         point first (equilibrium_iterations: modified Newton on the
!>                         factored S~, or NEWTON=FULL)
!>   commit_substep        strains, stresses, histories (eq. [24]) and
!>                         U, U', U'' (eqs. [40]-[42]) at the sub-step's end
!> The right side of eq. [36] is written in residual form: with F(sigma_t)
!> the internal force of the current stresses it also carries the out-of-
!> balance force R_t - F_t - M U''_t that the printed eq. [36] drops (Wilson-
!> theta does not hold equilibrium at t + dt); keeping it makes the step
!> exactly Bathe and Wilson's total form and keeps round-off from drifting.
!>
!> S~ depends on dt and on the supports only: it is factored once per TIME
!> stage (and row). The equations the plate holds are imposed through a
!> capacitance (Schur-complement) system on that factor (module
!> visco2d_capacitance): a change of the contact set costs one
!> back-substitution per new held equation, not a refactorization
!> (contact_hold_t, the stepper's hold). A test extends that type to refactor
!> S~ with the held equations eliminated instead, to check the capacitance
!> system against it (test/visco2d_refactoring.f90); no branch here knows of it.
!> The stages time themselves for `--timing` (visco2d_timers).
module visco2d_time_step
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, kinematics_large
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, short_real
  use visco2d_deck, only: deck_t
  use visco2d_material, only: has_memory
  use visco2d_plastic_step, only: plastic_trial_stress, plastic_work, yield_limits, plastic_point_tangents
  use visco2d_element, only: gauss_count
  use visco2d_operators, only: operators_t, operators_create, operators_trial_stress, operators_element_force
  use visco2d_banded, only: band_matrix_t, band_multiply_rows, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card, solver_default, solve_failure_text
  use visco2d_assembly, only: assemble_stiffness, assemble_point_tangents, external_load, support_mask, node_dof, &
                              prescribed_displacement, &
                              scatter_add, lumped_mass, gravity_load
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients, element_terms, viscoelastic_state_t
  use visco2d_constitutive, only: history_stresses, commit_history
  use visco2d_contact, only: contact_t, contact_create, contact_held_dofs, contact_begin_increment, contact_search, &
                             contact_gap, contact_release_tensile, pair_on_surface
  use visco2d_capacitance, only: capacitance_t, capacitance_reset, capacitance_set, capacitance_apply, &
                                 capacitance_partners, constraint_sum
  use visco2d_pad_mesh, only: is_pad_node
  use visco2d_pad_projection, only: project_on_surface
  use visco2d_timers, only: timer_start, timer_stop, phase_solve, phase_constitutive, phase_contact, &
                            phase_factorization, phase_assembly
  use visco2d_integrators, only: integrator_t, substep_t, integrator_create, solve_interval, mass_coefficient, &
                                 inertia_load, solve_point_inertia, update_kinematics
  use visco2d_dynamic_state, only: dynamic_state_t
  use visco2d_body_mesh, only: contact_card_line, contact_card_name
  use visco2d_finite_assembly, only: finite_assemble, strain_extremes, finite_memory_t, finite_memory_create, &
                                     memory_points_create
  use visco2d_finite_force, only: finite_reference_t, finite_reference_create, lean_forces, gradient_strains
  use visco2d_finite_viscoelastic, only: viscoelastic_point_t
  implicit none
  private

  public :: stepper_t, solve_point_t, contact_hold_t, stepper_create, effective_stiffness, factor_effective, &
            effective_load, solve_supports, contact_repeat, commit_substep, hold_contact, solve_point_state
  public :: dynamic_force_tolerance, dynamic_energy_tolerance

  !> A step with plasticity has converged when the force residual on the free
  !> equations is at most dynamic_force_tolerance of the largest of the
  !> step's force vectors (R~ with the forces of the start state, c M dU,
  !> F(sigma)) and the energy of the next correction |dU_next . r| at most
  !> dynamic_energy_tolerance of the first solve's |dU_1 . R~|.
  real(dp), parameter :: dynamic_force_tolerance = 1.0e-5_dp
  real(dp), parameter :: dynamic_energy_tolerance = 1.0e-10_dp

  !> The solve point of one row: its intervals, S~ and its factor, the
  !> capacitance system of the held equations on that factor, and the step
  !> constants of the viscoelastic law over h (the solve) and over the
  !> sub-step (the stress update).
  type :: solve_point_t
    type(substep_t) :: row
    real(dp) :: length = 0.0_dp                     !< the sub-step, fraction dt
    real(dp) :: h = 0.0_dp                          !< the solve interval, theta length
    type(band_matrix_t) :: effective                !< S~ (eq. [35]), unconstrained
    type(factor_t) :: factor                        !< its Cholesky factor with the supports imposed
    type(capacitance_t) :: capacitance
    type(step_coefficients_t), allocatable :: over_h(:), over_length(:)   !< per material
    real(dp), allocatable :: shear(:), bulk(:)      !< per element, over the sub-step
    real(dp), allocatable :: shear_h(:), bulk_h(:)  !< per element, over h
  end type solve_point_t

  !> How the plate's held equations enter eq. [34]: the program's way, this
  !> type, factors S~ once with the supports and imposes the held equations
  !> by the capacitance system on that factor (visco2d_capacitance; a PAD's
  !> multi-point constraints need it). Its three bindings are all the step
  !> knows of it; a test extends it to check the capacitance system against
  !> refactoring S~ with the held equations eliminated (test/visco2d_refactoring.f90).
  type :: contact_hold_t
  contains
    procedure, nopass :: factor => capacitance_factor   !< S~ of row r factored, the held set put in
    procedure, nopass :: hold => capacitance_hold       !< the contact set has changed
    procedure, nopass :: solve => capacitance_solve     !< dU of row r with the held equations
  end type contact_hold_t

  !> What the step needs besides the state: the integrator and its solve
  !> points, the operators, mass and gravity, supports and the plate's held
  !> equations, and the step's work arrays (the values at the sub-step's end:
  !> load_next, internal_next, reaction_next, target_next).
  type :: stepper_t
    type(integrator_t) :: integrator
    type(solve_point_t), allocatable :: points(:)
    type(operators_t) :: operators
    real(dp), allocatable :: mass(:), gravity(:)
    logical, allocatable :: supports(:), fixed(:), held(:)
    integer, allocatable :: held_rows(:)          !< the equations held by the plate
    logical, allocatable :: pad(:)                !< the pad's equations (PAD), else none
    logical :: memory = .false., contact_on = .false.
    class(contact_hold_t), allocatable :: hold     !< how the held equations are imposed (contact_hold_t)
    integer :: solver = solver_default             !< the factor's storage (SOLVER card, visco2d_factor)
    type(contact_t) :: contact
    integer :: factorizations = 0
    real(dp) :: touch_fraction = 1.0_dp            !< earliest touch in the sub-step (0..1)
    real(dp), allocatable :: reaction_solve(:)     !< plate reactions at the solve point
    real(dp), allocatable :: effective_load(:), support_solution(:), solution(:), prescribed(:), du(:), dv(:), da(:)
    real(dp), allocatable :: load_next(:), internal_next(:), reaction_next(:), target_next(:)
    real(dp), allocatable :: trial(:, :, :), increments(:, :, :), history_h(:, :, :), history_length(:, :, :)
    !> The state at the solve point t + h when h is not the sub-step (Wilson-theta; solve_point_state).
    real(dp), allocatable :: stress_solve(:, :, :), strain_solve(:, :, :), increments_solve(:, :, :), internal_solve(:)
    type(viscoelastic_state_t) :: history_solve
    !> With a PLASTIC material (plastic): ebar and de_p of the sub-step's
    !> trial stresses and of the solve point's; the residual at the solve
    !> point (its held rows are the plate's reactions); the iteration counts.
    logical :: plastic = .false.
    integer :: iterations_allowed = 50             !< ITERATIONS= of ANALYSIS DYNAMIC
    real(dp), allocatable :: trial_ebar(:, :), plastic_increments(:, :, :), ebar_solve(:, :), plastic_solve(:, :, :)
    real(dp), allocatable :: yield_limit(:, :)     !< (2/3) sigma_y(ebar)^2 of the state (yield_limits)
    real(dp), allocatable :: residual(:), correction(:), no_values(:)
    real(dp), allocatable :: plastic_correction(:) !< dU less the linear solve's at the last yielding solve (the predictor)
    logical :: full_newton = .false.               !< NEWTON=FULL: the consistent tangent factored at each iteration
    type(band_matrix_t) :: tangent                 !< its S_t = c M + (1 - alpha_f) K_t (NEWTON=FULL)
    real(dp), allocatable :: point_tangents(:, :, :, :)   !< (4, 4, gauss, nelem) the consistent tangents of K_t
    type(factor_t) :: tangent_factor               !< S_t factored with the supports imposed
    type(capacitance_t) :: tangent_capacitance     !< the held equations on that factor
    integer :: tangent_factorizations = 0          !< the factorizations of S_t
    integer :: iterations = 0                      !< equilibrium iterations, all sub-steps
    integer :: iterations_max = 0                  !< the most in one solve
    integer :: iterated_solves = 0                 !< solves in which a Gauss point yielded
    real(dp) :: plastic_dissipation = 0.0_dp       !< sum of plastic_work over the sub-steps, J per radian
    !> With KINEMATICS LARGE (finite): the internal force, the Cauchy stresses
    !> and the logarithmic strains are those of the hyperelastic bodies at U
    !> (visco2d_finite_assembly), and every solve is iterated to equilibrium
    !> as a plastic one is (equilibrium_iterations); the stored energy W at
    !> the sub-step's end and at the solve point, the element an evaluation
    !> found inverted (0: none), and the extremes of the deformation over the run.
    logical :: finite = .false.
    type(finite_reference_t) :: reference          !< the reference configuration of the lean pass (visco2d_finite_force)
    real(dp), allocatable :: gradient_next(:, :, :), gradient_solve(:, :, :)   !< H of the lean pass, (5, gauss, nelem)
    real(dp) :: energy_next = 0.0_dp, energy_solve = 0.0_dp
    integer :: inverted = 0
    real(dp) :: volume_ratio_min = 1.0_dp, volume_ratio_max = 1.0_dp, stretch_min = 1.0_dp
    integer :: halvings = 0                        !< corrections halved because they inverted an element
    !> KINEMATICS LARGE with materials that relax (PRONY terms): their finite-strain laws (Simo's
    !> viscoelasticity) and the Gauss points' histories at the sub-step's end and at the solve point.
    logical :: relaxing = .false.
    type(finite_memory_t) :: finite_memory
    type(viscoelastic_point_t), allocatable :: history_next(:, :), history_at_solve(:, :)
  end type stepper_t

contains

  !> The stepper of a deck: integrator rows, mass (eq. [32]), gravity, supports,
  !> operators, the contact state, work arrays; `hold` (tests only) another
  !> way to impose the held equations than the capacitance system.
  subroutine stepper_create(deck, stepper, hold)
    type(deck_t), intent(in) :: deck
    type(stepper_t), intent(out) :: stepper
    class(contact_hold_t), intent(in), optional :: hold
    integer :: k, n, nmat
    associate (mesh => deck%mesh, materials => deck%materials)
    n = 2*mesh%nnode
    nmat = size(materials)
    stepper%integrator = integrator_create(deck%dynamics)
    if (present(hold)) then
      allocate(stepper%hold, source=hold)
    else
      allocate(contact_hold_t :: stepper%hold)
    end if
    stepper%solver = solver_of_card(deck%settings%solver)
    do k = 1, nmat
      if (has_memory(materials(k)) .and. any(mesh%element_material == k)) stepper%memory = .true.
    end do
    stepper%contact_on = deck%plate%line > 0 .or. deck%body%line > 0   ! the plate, or a second BODY
    do k = 1, nmat
      if (materials(k)%plastic .and. any(mesh%element_material == k)) stepper%plastic = .true.
    end do
    stepper%finite = deck%settings%kinematics == kinematics_large
    if (stepper%finite) then
      stepper%iterations_allowed = deck%settings%iterations
      stepper%full_newton = deck%settings%full_newton
      allocate(stepper%residual(n), stepper%correction(n), stepper%no_values(n))
      stepper%no_values = 0.0_dp
      stepper%reference = finite_reference_create(mesh, materials, deck%settings)
      call finite_memory_create(mesh, materials, stepper%finite_memory, stepper%relaxing)
      stepper%memory = .false.                     ! the histories are the finite-strain law's, not eq. [24]'s
      if (stepper%relaxing) then
        stepper%history_next = memory_points_create(mesh, stepper%finite_memory)
        stepper%history_at_solve = stepper%history_next
      end if
      allocate(stepper%gradient_next(5, gauss_count, mesh%nelem), stepper%gradient_solve(5, gauss_count, mesh%nelem))
    end if
    if (stepper%plastic) then
      stepper%iterations_allowed = deck%settings%iterations
      stepper%full_newton = deck%settings%full_newton
      allocate(stepper%trial_ebar(gauss_count, mesh%nelem), stepper%ebar_solve(gauss_count, mesh%nelem), &
               stepper%plastic_increments(4, gauss_count, mesh%nelem), stepper%plastic_solve(4, gauss_count, mesh%nelem), &
               stepper%residual(n), stepper%correction(n), stepper%no_values(n), stepper%yield_limit(gauss_count, mesh%nelem))
      stepper%no_values = 0.0_dp
      stepper%trial_ebar = 0.0_dp
      call yield_limits(materials, mesh%element_material, stepper%trial_ebar, stepper%yield_limit)
    end if
    allocate(stepper%points(size(stepper%integrator%rows)))
    do k = 1, size(stepper%points)
      stepper%points(k)%row = stepper%integrator%rows(k)
      allocate(stepper%points(k)%over_h(nmat), stepper%points(k)%over_length(nmat))
    end do
    stepper%supports = support_mask(deck%mesh, deck%settings, deck%loads)
    stepper%fixed = stepper%supports
    allocate(stepper%held_rows(0), stepper%held(n), stepper%reaction_solve(n))
    stepper%held = .false.
    stepper%reaction_solve = 0.0_dp
    stepper%mass = lumped_mass(deck%mesh, deck%settings, deck%materials)                ! eq. [32], row sums
    stepper%gravity = gravity_load(deck%mesh, deck%settings, deck%materials, deck%loads)
    call operators_create(deck, stepper%operators)
    allocate(stepper%effective_load(n), stepper%support_solution(n), stepper%solution(n), stepper%prescribed(n), stepper%du(n), &
             stepper%dv(n), stepper%da(n), stepper%load_next(n), stepper%internal_next(n), stepper%reaction_next(n), &
             stepper%target_next(n))
    allocate(stepper%trial(4, gauss_count, mesh%nelem), stepper%increments(4, gauss_count, mesh%nelem))
    if (stepper%memory) allocate(stepper%history_h(4, gauss_count, mesh%nelem), &
                                 stepper%history_length(4, gauss_count, mesh%nelem))
    allocate(stepper%pad(n))
    stepper%pad = .false.
    if (stepper%contact_on) call contact_create(deck, stepper%contact)
    if (stepper%contact_on .and. stepper%contact%pad) call pad_constraints(stepper, deck)
    end associate
  end subroutine stepper_create

  !> With a PAD: its equations (no gravity on the pad, at rest at t = 0), and
  !> the constraint of each body equation that may touch it: the pad surface
  !> equations under the node, in the same direction, with their weights
  !> (supported ones left out: they do not move), into every row's
  !> capacitance system. Only it imposes multi-point constraints: with a pad
  !> the hold is the program's (contact_hold_t), whatever was asked.
  subroutine pad_constraints(stepper, deck)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer :: node, r
    associate (mesh => deck%mesh)
    deallocate(stepper%hold)
    allocate(contact_hold_t :: stepper%hold)
    do node = 1, mesh%nnode
      if (is_pad_node(deck, node)) stepper%pad(node_dof(mesh, node, 1):node_dof(mesh, node, 2)) = .true.
    end do
    stepper%gravity = merge(0.0_dp, stepper%gravity, stepper%pad)
    do r = 1, size(stepper%points)
      call capacitance_partners(stepper%points(r)%capacitance, stepper%contact%partner, stepper%contact%weight)
    end do
    ! NEWTON=FULL's own capacitance system on the tangent's factor holds the same constraints
    call capacitance_partners(stepper%tangent_capacitance, stepper%contact%partner, stepper%contact%weight)
    end associate
  end subroutine pad_constraints

  !> sum_k w_k x(partner_k) of equation c's constraint (0 on the rigid plate).
  pure real(dp) function partner_sum(stepper, x, c) result(total)
    type(stepper_t), intent(in) :: stepper
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: c
    total = constraint_sum(stepper%contact%partner, stepper%contact%weight, x, c)
  end function partner_sum

  !> Eq. [35] for row r and time step dt: S~ = (1 - alpha_f) S_h + c M, S_h
  !> assembled with the moduli over the solve interval h; also the step
  !> constants over the sub-step for the stress update. `stiffness_rows`
  !> returns the absolute row sums of S_h (for the instability bound).
  subroutine effective_stiffness(stepper, deck, r, dt, stiffness_rows)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    real(dp), intent(in) :: dt
    real(dp), intent(out) :: stiffness_rows(:)
    integer :: m, i, j
    associate (point => stepper%points(r), material_of => deck%mesh%element_material)
    point%length = point%row%fraction*dt
    point%h = solve_interval(point%row, point%length)
    do m = 1, size(deck%materials)
      point%over_h(m) = step_coefficients(deck%materials(m), point%h)
      point%over_length(m) = step_coefficients(deck%materials(m), point%length)
    end do
    point%shear = point%over_length(material_of)%shear
    point%bulk = point%over_length(material_of)%bulk
    point%shear_h = point%over_h(material_of)%shear
    point%bulk_h = point%over_h(material_of)%bulk
    call assemble_stiffness(deck%mesh, deck%settings, point%over_h(material_of)%shear, point%over_h(material_of)%bulk, &
                            point%effective)
    stiffness_rows = 0.0_dp
    associate (effective => point%effective)
    do j = 1, effective%n
      do i = j, min(effective%n, j + effective%kd)
        stiffness_rows(j) = stiffness_rows(j) + abs(effective%ab(1 + i - j, j))
        if (i /= j) stiffness_rows(i) = stiffness_rows(i) + abs(effective%ab(1 + i - j, j))
      end do
    end do
    if (point%row%alpha_f /= 0.0_dp) effective%ab = (1.0_dp - point%row%alpha_f)*effective%ab
    effective%ab(1, :) = effective%ab(1, :) + mass_coefficient(point%row, point%h)*stepper%mass
    end associate
    end associate
  end subroutine effective_stiffness

  !> S~ of row r factored (visco2d_factor) and the held equations put in, as
  !> the stepper's hold does it (contact_hold_t: the supports imposed, the held
  !> equations in the capacitance system); info > 0: not positive definite at
  !> that equation, < 0: the capacitance matrix; `error` if a solve failed.
  subroutine factor_effective(stepper, r, info, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    call stepper%hold%factor(stepper, r, info, error)
  end subroutine factor_effective

  !> The contact set has changed: the held equations into every row (the
  !> stepper's hold). info > 0: S~ not positive definite; < 0: the
  !> capacitance matrix; `error`: a solve with the factor failed.
  subroutine hold_contact(stepper, info, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    call stepper%hold%hold(stepper, info, error)
  end subroutine hold_contact

  !> contact_hold_t's factor: S~ of row r factored with the supports imposed,
  !> then the held equations into its capacitance system.
  subroutine capacitance_factor(stepper, r, info, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    associate (point => stepper%points(r))
    call factor_compute(point%factor, point%effective, stepper%supports, info, stepper%solver)
    stepper%factorizations = stepper%factorizations + 1
    if (info > 0) return
    call capacitance_reset(point%capacitance, point%factor%n)
    if (stepper%contact_on) call capacitance_set(point%capacitance, point%factor, &
                                                 stepper%held .and. .not. stepper%supports, info, error)
    if (info > 0) info = -info                      ! the capacitance matrix, not S~
    end associate
  end subroutine capacitance_factor

  !> contact_hold_t's hold: the held equations into every row's capacitance
  !> system (a column per new equation, no new factor of S~).
  subroutine capacitance_hold(stepper, info, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    integer :: r
    info = 0
    do r = 1, size(stepper%points)
      call capacitance_set(stepper%points(r)%capacitance, stepper%points(r)%factor, &
                           stepper%held .and. .not. stepper%supports, info, error)
      info = -info
      if (info /= 0 .or. allocated(error)) return
    end do
  end subroutine capacitance_hold

  !> contact_hold_t's solve: dU of eq. [34] with the held equations, the
  !> capacitance correction of `support_solution` (solve_supports).
  subroutine capacitance_solve(stepper, r, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    type(error_t), allocatable, intent(inout) :: error
    stepper%solution = stepper%support_solution
    if (stepper%contact_on) call capacitance_apply(stepper%points(r)%capacitance, stepper%prescribed, &
                                                   stepper%solution)
  end subroutine capacitance_solve

  !> Eq. [36] for row r from `state` (at the sub-step's start; `start` is the
  !> state at the step's start) to t_next, into stepper%effective_load:
  !>   R~ = R_t + theta (1 - alpha_f)(R_next - R_t) + G - F(sigma_t) - (1 - alpha_f) F(s0_h) + M b
  !> with b the integrator's mass part (6/tau U'_t + 2 U''_t for Wilson-theta)
  !> and s0_h the history stress of eq. [23] over h as a pseudo-load; the
  !> history stress over the sub-step (for the trial stresses) is kept.
  !> Timed as the constitutive update (`--timing`).
  subroutine effective_load(stepper, deck, r, state, start, t_next)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    type(dynamic_state_t), intent(in) :: state, start
    real(dp), intent(in) :: t_next
    call timer_start(phase_constitutive)
    associate (point => stepper%points(r), row => stepper%points(r)%row)
    stepper%load_next = external_load(deck%mesh, deck%settings, deck%loads, t_next)
    stepper%target_next = prescribed_displacement(deck%mesh, deck%loads, t_next)
    stepper%effective_load = state%load + row%theta*(1.0_dp - row%alpha_f)*(stepper%load_next - state%load) + stepper%gravity &
                   - state%internal + stepper%mass*inertia_load(row, point%h, state%u, state%v, state%a, start%u, start%v)
    end associate
    if (stepper%memory) call add_history_load(stepper, deck, r, state)
    call timer_stop(phase_constitutive)
  end subroutine effective_load

  !> The memory part of eq. [36] for row r: the history stress s0_h of eq.
  !> [23] over h as the pseudo-load -(1 - alpha_f) F(s0_h) on stepper%effective_load,
  !> and the history stress over the sub-step kept (for the trial stresses).
  subroutine add_history_load(stepper, deck, r, state)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    type(dynamic_state_t), intent(in) :: state
    integer :: e
    associate (point => stepper%points(r), row => stepper%points(r)%row)
    call history_stresses(deck%materials, deck%mesh%element_material, state%history, point%over_h, stepper%history_h)
    if (point%h == point%length) then
      stepper%history_length = stepper%history_h
    else
      call history_stresses(deck%materials, deck%mesh%element_material, state%history, point%over_length, &
                            stepper%history_length)
    end if
    do e = 1, deck%mesh%nelem
      if (element_terms(state%history, e) == 0) cycle
      if (row%alpha_f == 0.0_dp) then
        call scatter_add(deck%mesh, e, -operators_element_force(stepper%operators, e, stepper%history_h(:, :, e)), &
                         stepper%effective_load)
      else
        call scatter_add(deck%mesh, e, -(1.0_dp - row%alpha_f)* &
                         operators_element_force(stepper%operators, e, stepper%history_h(:, :, e)), stepper%effective_load)
      end if
    end do
    end associate
  end subroutine add_history_load

  !> Eq. [34] with the supports only, once per sub-step: the prescribed
  !> values at the solve point (fraction theta of their change) and
  !> free = S~^-1 R~. A repeat after a contact change only changes the
  !> capacitance correction of `free`.
  subroutine solve_supports(stepper, r, state, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    type(dynamic_state_t), intent(in) :: state
    type(error_t), allocatable, intent(inout) :: error
    integer :: status
    call timer_start(phase_solve)
    associate (point => stepper%points(r))
    stepper%prescribed = state%target + point%row%theta*(stepper%target_next - state%target) - state%u
    if (stepper%contact_on) then
      call contact_begin_increment(stepper%contact)
      stepper%touch_fraction = 1.0_dp
    end if
    stepper%support_solution = stepper%effective_load
    call band_constrain_rhs(point%effective, stepper%supports, stepper%prescribed, stepper%support_solution)
    call factor_solve(point%factor, stepper%support_solution, status)                     ! eq. [34] without contact
    if (status /= 0) call set_error(error, solve_failure_text(status))
    end associate
    call timer_stop(phase_solve)
  end subroutine solve_supports

  !> The contact repeat of row r (each stage it calls times itself for
  !> `--timing`): dU with the plate's conditions (eq. [34]),
  !> the plate reactions at the solve point, the increments to the
  !> sub-step's end (eqs. [37]-[39]) and the trial stresses (eqs. [13], [14],
  !> [23]); with a plate, repeated while the contact search changes the set
  !> (the paper's iteration). finite = .false.: dU or dU'' is not finite.
  subroutine contact_repeat(stepper, deck, r, state, start, finite, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    type(dynamic_state_t), intent(in) :: state, start
    logical, intent(out) :: finite
    type(error_t), allocatable, intent(inout) :: error
    logical :: changed
    real(dp) :: fraction
    finite = .true.
    associate (point => stepper%points(r), row => stepper%points(r)%row)
    if (stepper%finite .and. stepper%contact%pad) call follow_pairing(stepper, deck, state%u, error)
    if (allocated(error)) return
    if (stepper%contact_on) then                                        ! a PAD's releases (contact_release_tensile)
      call contact_release_tensile(deck, stepper%contact, stepper%reaction_solve, changed)
      if (changed) call new_contact_set(stepper, deck, error)
      if (allocated(error)) return
    end if
    do
      if (stepper%contact_on) call adjusted_displacements(stepper, deck, state%u, row%theta)
      call solve_held(stepper, r, error)
      if (allocated(error)) return
      if (stepper%plastic .or. stepper%finite) call equilibrium_iterations(stepper, deck, r, state, error)
      if (allocated(error)) return
      if (stepper%contact_on) call solve_point_reactions(stepper, r, state, start)
      call update_kinematics(row, point%length, stepper%solution, state%u, state%v, state%a, start%u, start%v, &
                             stepper%du, stepper%dv, stepper%da)                       ! eqs. [37]-[39]
      if (stepper%contact_on) then                                      ! held on the plate: U'' = U' = 0
        call adjusted_displacements(stepper, deck, state%u, 1.0_dp)
        call follow_surface(stepper, state, error, deck)
        if (allocated(error)) return
      end if
      if (.not. all(ieee_is_finite(stepper%da)) .or. .not. all(ieee_is_finite(stepper%du))) then
        finite = .false.
        return
      end if
      call trial_stresses(stepper, deck, point, state)
      if (stepper%inverted > 0) then
        call set_error(error, 'element '//integer_text(deck%mesh%element_id(stepper%inverted))//' inverts at the '// &
          'end of the step (KINEMATICS LARGE): the deformation is beyond what this mesh can follow in one step; '// &
          'use a smaller DT or a finer mesh')
        return
      end if
      stepper%reaction_next = merge(stepper%mass*(state%a + stepper%da) + stepper%internal_next - stepper%load_next &
                                    - stepper%gravity, 0.0_dp, rigid_reactions(stepper))
      if (.not. stepper%contact_on) exit
      call search_contact(stepper, deck, state, changed, fraction)
      if (.not. changed) exit
      stepper%touch_fraction = min(stepper%touch_fraction, fraction)
      call new_contact_set(stepper, deck, error)
      if (allocated(error)) return
    end do
    end associate
  end subroutine contact_repeat

  !> The equations whose reactions are the rigid plate's and the supports':
  !> the supports, and on the rigid plate the held equations. On a PAD the
  !> held equations are the body's side of a constraint with the pad, an
  !> internal force (the pad's side acts on the surface nodes), so they are
  !> left out: the rigid plate's force then comes through the pad's supported
  !> bottom only, and reaction_z_N is that force, not twice it.
  pure function rigid_reactions(stepper) result(mask)
    type(stepper_t), intent(in) :: stepper
    logical :: mask(size(stepper%fixed))
    if (stepper%contact_on) then
      mask = stepper%supports .or. (stepper%held .and. .not. stepper%contact%pad)
    else
      mask = stepper%fixed
    end if
  end function rigid_reactions

  !> The contact set has changed: the held equations and rows, into every
  !> row's capacitance system (hold_contact); an error at the PLATE card if
  !> a matrix is not positive definite.
  subroutine new_contact_set(stepper, deck, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: i, info
    stepper%held = contact_held_dofs(deck, stepper%contact)
    stepper%fixed = stepper%supports .or. stepper%held
    stepper%held_rows = pack([(i, i = 1, size(stepper%held))], stepper%held)
    call timer_start(phase_factorization)
    call hold_contact(stepper, info, error)
    call timer_stop(phase_factorization)
    if (allocated(error)) return
    if (info > 0) then
      call set_error(error, 'the effective stiffness is not positive definite at equation '//integer_text(info)// &
        ' after a contact change', file=deck%cards%file, line=contact_card_line(deck, .false.), &
        card=contact_card_name(deck, .false.))
    else if (info < 0) then
      call set_error(error, 'the contact capacitance matrix is not positive definite (equation '//integer_text(-info)// &
        ' of the held set)', file=deck%cards%file, line=contact_card_line(deck, .false.), &
        card=contact_card_name(deck, .false.))
    end if
  end subroutine new_contact_set

  !> KINEMATICS LARGE with a PAD, at the start of a sub-step: each body node
  !> paired with the pad surface under its current radius (pair_on_surface),
  !> so that a held node follows the deformed surface as the two slide; when
  !> a pairing changed (nearly every step while the surfaces slide), every
  !> capacitance system takes the new constraints (its columns computed anew:
  !> one back-substitution per held equation and row). Measured on the peach
  !> on the pad (doc/finite.md): 16 % more CPU, the peer code's force to
  !> 0.04 % where the undeformed pairing was 4 % low.
  subroutine follow_pairing(stepper, deck, u, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: u(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp), parameter :: pairing_tolerance = 1.0e-12_dp   !< a change of s below this keeps the pairing
    logical :: changed
    integer :: r
    call timer_start(phase_contact)
    call pair_on_surface(deck, stepper%contact, u, pairing_tolerance, changed)
    call timer_stop(phase_contact)
    if (.not. changed) return
    do r = 1, size(stepper%points)
      call capacitance_partners(stepper%points(r)%capacitance, stepper%contact%partner, stepper%contact%weight)
      call capacitance_reset(stepper%points(r)%capacitance, stepper%points(r)%factor%n)
    end do
    call capacitance_partners(stepper%tangent_capacitance, stepper%contact%partner, stepper%contact%weight)
    call new_contact_set(stepper, deck, error)
  end subroutine follow_pairing

  !> A held equation moves with the surface under it at the sub-step's end:
  !> U = U_surface + value, U' = U'_surface, U'' = U''_surface. On the fixed
  !> plate (U' = U'' = 0 there, U the adjusted displacement) the node is put
  !> there. On a PAD the pair (the body node and the surface nodes under it)
  !> is put on its constraint by the mass-metric correction of
  !> visco2d_pad_projection, an inelastic collision that keeps the momentum
  !> and cannot add energy; supported equations keep their values.
  subroutine follow_surface(stepper, state, error, deck)
    type(stepper_t), intent(inout) :: stepper
    type(dynamic_state_t), intent(in) :: state
    type(error_t), allocatable, intent(inout) :: error
    type(deck_t), intent(in) :: deck
    real(dp), allocatable :: vectors(:, :), targets(:, :)
    integer, allocatable :: rows(:)
    integer :: i, c, info
    if (.not. stepper%contact%pad) then
      do i = 1, size(stepper%held_rows)
        c = stepper%held_rows(i)
        stepper%du(c) = stepper%prescribed(c)
        stepper%dv(c) = -state%v(c)
        stepper%da(c) = -state%a(c)
      end do
      return
    end if
    rows = pack(stepper%held_rows, .not. stepper%supports(stepper%held_rows))
    allocate(targets(size(rows), 3))
    targets(:, 1) = stepper%prescribed(rows)
    targets(:, 2:3) = 0.0_dp
    vectors = reshape([stepper%du, state%v + stepper%dv, state%a + stepper%da], [size(stepper%du), 3])
    call project_on_surface(stepper%contact%partner, stepper%contact%weight, stepper%mass, rows, targets, &
                            vectors, info)
    if (info /= 0) then
      call set_error(error, 'the pad contact constraints are dependent (equation '//integer_text(info)// &
        ' of the held set): two body nodes hold the same pad surface equation in the same way', &
        file=deck%cards%file, line=contact_card_line(deck, .true.), &
        card=contact_card_name(deck, .true.))
      return
    end if
    stepper%du = vectors(:, 1)
    stepper%dv = vectors(:, 2) - state%v
    stepper%da = vectors(:, 3) - state%a
  end subroutine follow_surface

  !> dU of eq. [34] with the held equations, as the stepper's hold imposes
  !> them (contact_hold_t: the capacitance correction of `support_solution`).
  subroutine solve_held(stepper, r, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    type(error_t), allocatable, intent(inout) :: error
    call timer_start(phase_solve)
    call stepper%hold%solve(stepper, r, error)
    call timer_stop(phase_solve)
  end subroutine solve_held

  !> The contact search after a trial increment (visco2d_contact): `changed`
  !> if the set changes, `fraction` the earliest touch. Timed as contact.
  subroutine search_contact(stepper, deck, state, changed, fraction)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    type(dynamic_state_t), intent(in) :: state
    logical, intent(out) :: changed
    real(dp), intent(out) :: fraction
    call timer_start(phase_contact)
    call contact_search(deck, stepper%contact, state%u, stepper%du, stepper%reaction_solve, changed, fraction)
    call timer_stop(phase_contact)
  end subroutine search_contact

  !> The plate reactions at the solve point (t + theta dt for Wilson-theta,
  !> the sub-step's end otherwise), where the integrator holds equilibrium:
  !> the residual S~ dU - R~ of eq. [34] on the held rows, without the
  !> inertia M a of the held node itself. At t + dt a held node's Wilson-
  !> theta reaction carries the stiff modes a contact event excites, damped
  !> only by the limit spectral radius (-0.78 per step at theta = 1.4), so it
  !> would flip sign from step to step (spikes of 5x the impact force at
  !> nu = 0.4999, release/recapture chatter with RELEASE=YES). The inertia of
  !> the held node is zero once it is held; in the step it touches, it is
  !> the impulse that stops the node's mass (contact_loss_J), not a pressure.
  subroutine solve_point_reactions(stepper, r, state, start)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    type(dynamic_state_t), intent(in) :: state, start
    real(dp) :: inertia(size(stepper%solution))
    integer :: i
    associate (point => stepper%points(r), p => stepper%held_rows)
    inertia = solve_point_inertia(point%row, point%h, stepper%solution, state%u, state%v, state%a, start%u, start%v)
    stepper%reaction_solve = 0.0_dp
    if (stepper%plastic .or. stepper%finite) then   ! the residual of the converged iteration
      stepper%reaction_solve(p) = -stepper%residual(p)
    else
      stepper%reaction_solve(p) = band_multiply_rows(point%effective, stepper%solution, p) - stepper%effective_load(p)
    end if
    do i = 1, size(p)                               ! less the inertia relative to the surface under the node
      stepper%reaction_solve(p(i)) = stepper%reaction_solve(p(i)) &
                                     - stepper%mass(p(i))*(inertia(p(i)) - partner_sum(stepper, inertia, p(i)))
    end do
    end associate
  end subroutine solve_point_reactions

  !> The trial stresses over the sub-step (eqs. [13], [14] with the history
  !> stress of eq. [23]) from the increment du, and their internal force.
  subroutine trial_stresses(stepper, deck, point, state)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    type(solve_point_t), intent(in) :: point
    type(dynamic_state_t), intent(in) :: state
    integer :: yielded
    call timer_start(phase_constitutive)
    if (stepper%finite) then              ! the bodies at U + dU; increments: the change of the logarithmic strain
      stepper%finite_memory%dt = point%length
      if (stepper%relaxing) then          ! the histories only when kept (finite_assemble's note)
        call lean_forces(stepper%reference, deck%mesh, deck%materials, deck%settings, state%u + stepper%du, &
                         stepper%internal_next, stepper%trial, stepper%energy_next, stepper%inverted, &
                         stepper%gradient_next, stepper%increments, stepper%finite_memory, state%finite_history, &
                         stepper%history_next)
      else
        call lean_forces(stepper%reference, deck%mesh, deck%materials, deck%settings, state%u + stepper%du, &
                         stepper%internal_next, stepper%trial, stepper%energy_next, stepper%inverted, &
                         stepper%gradient_next, stepper%increments)
      end if
      if (stepper%inverted == 0) call gradient_strains(stepper%reference, stepper%gradient_next, stepper%increments)
      stepper%increments = stepper%increments - state%strain
    else if (stepper%plastic) then        ! the return mapping at the sub-step's end (history_length: absent without memory)
      call plastic_trial_stress(stepper%operators, deck%materials, deck%mesh%element_material, stepper%yield_limit, &
                                stepper%du, point%shear, point%bulk, state%stress, state%ebar, stepper%increments, &
                                stepper%trial, stepper%internal_next, stepper%trial_ebar, stepper%plastic_increments, &
                                yielded, stepper%history_length)
    else if (stepper%memory) then
      call operators_trial_stress(stepper%operators, stepper%du, point%shear, point%bulk, state%stress, &
                                  stepper%increments, stepper%trial, stepper%internal_next, stepper%history_length)
    else
      call operators_trial_stress(stepper%operators, stepper%du, point%shear, point%bulk, state%stress, &
                                  stepper%increments, stepper%trial, stepper%internal_next)
    end if
    call timer_stop(phase_constitutive)
  end subroutine trial_stresses

  !> The adjusted displacements of the contact conditions, into
  !> stepper%prescribed: a contact node's u_z goes to the plate over the
  !> sub-step (0 once it is there), u_r stays (STICK); `fraction` = theta
  !> gives the values at the solve point. Supports keep their own values.
  subroutine adjusted_displacements(stepper, deck, u, fraction)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: u(:)
    real(dp), intent(in) :: fraction
    integer :: i, node
    associate (contact => stepper%contact)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. contact%active(node)) cycle
      associate (r => node_dof(deck%mesh, node, 1), z => node_dof(deck%mesh, node, 2))
      if (.not. stepper%supports(z)) stepper%prescribed(z) = -fraction*contact_gap(deck, contact, u, node)
      if (contact%stick .and. .not. stepper%supports(r)) stepper%prescribed(r) = 0.0_dp
      end associate
    end do
    end associate
  end subroutine adjusted_displacements

  !> With a PLASTIC material: the solution dU of eq. [34] (the linear one on
  !> entry, with the supports and the held equations imposed) iterated to
  !> equilibrium at the solve point t + h by modified Newton on the factored
  !> S~ (the factor of the TIME stage: no new factorization). The residual
  !>   r(dU) = R~ + (1 - alpha_f)(F(sigma_t) + F(s0_h)) - c M dU - (1 - alpha_f) F(sigma_h(dU))
  !> is R~ - S~ dU where every Gauss point stays elastic, so an elastic solve
  !> ends at once; sigma_h(dU) is the return mapping over h from the step's
  !> start (plastic_solve_point). Each correction S~ d = r keeps the
  !> supports and the held equations where they are (the capacitance system
  !> with zero values). Converged: the force and energy criteria of
  !> dynamic_force_tolerance and dynamic_energy_tolerance; otherwise, after
  !> ITERATIONS= corrections, an error (located at the TIME card by the caller).
  subroutine equilibrium_iterations(stepper, deck, r, state, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    type(dynamic_state_t), intent(in) :: state
    type(error_t), allocatable, intent(inout) :: error
    real(dp), allocatable :: base(:), previous(:), difference(:), linear(:), reduced(:), taken(:)
    logical, allocatable :: free(:)
    logical :: predicted
    real(dp) :: c, kept, energy_first, energy, force_ratio, scale, relaxation, denominator
    integer :: iteration, yielded, e
    associate (point => stepper%points(r), row => stepper%points(r)%row)
    c = mass_coefficient(row, point%h)
    kept = 1.0_dp - row%alpha_f
    free = .not. (stepper%supports .or. stepper%held)
    base = stepper%effective_load + kept*state%internal            ! + (1 - alpha_f) F(s0_h), the history pseudo-load
    if (stepper%memory) then
      do e = 1, deck%mesh%nelem
        if (element_terms(state%history, e) == 0) cycle
        call scatter_add(deck%mesh, e, kept*operators_element_force(stepper%operators, e, stepper%history_h(:, :, e)), base)
      end do
    end if
    energy_first = abs(sum(stepper%solution*stepper%effective_load, mask=free))
    relaxation = 1.0_dp
    linear = stepper%solution
    predicted = allocated(stepper%plastic_correction)
    if (predicted) stepper%solution = stepper%solution + merge(stepper%plastic_correction, 0.0_dp, free)
    allocate(taken(size(stepper%solution)))
    taken = 0.0_dp
    do iteration = 1, stepper%iterations_allowed
      call timer_start(phase_constitutive)
      if (stepper%finite) then                       ! always iterated: f(U) is nonlinear
        call finite_solve_point(stepper, deck, state, point%h, iteration, taken, error)
        yielded = 1
      else
        call plastic_solve_point(stepper, deck, point, state, yielded)
      end if
      call timer_stop(phase_constitutive)
      if (allocated(error)) return
      stepper%residual = base - c*stepper%mass*stepper%solution - kept*stepper%internal_solve
      if (iteration == 1 .and. yielded == 0 .and. .not. predicted) exit   ! elastic: the linear solve is the answer
      scale = sqrt(max(sum(base**2, mask=free), kept**2*sum(stepper%internal_solve**2, mask=free), &
                       c**2*sum((stepper%mass*stepper%solution)**2, mask=free), tiny(1.0_dp)))
      reduced = reduced_residual(stepper, stepper%residual)
      force_ratio = sqrt(sum(reduced**2, mask=free))/scale
      stepper%correction = stepper%residual
      if (stepper%full_newton) then                  ! NEWTON=FULL: S_t d = r, S_t of this iterate
        call tangent_correction(stepper, deck, point, state, c, kept, error)
        if (allocated(error)) return
      else                                           ! modified Newton: S~ d = r on the TIME stage's factor
        call held_correction(stepper, point%effective, point%factor, point%capacitance, error)
        if (allocated(error)) return
      end if
      energy = abs(sum(stepper%correction*reduced, mask=free))
      if (.not. (ieee_is_finite(force_ratio) .and. ieee_is_finite(energy))) then
        call set_error(error, 'the equilibrium iteration of the '//step_name(stepper)//' diverged (iteration '// &
          integer_text(iteration)//': the residual is not finite); use a smaller DT')
        return
      end if
      if (force_ratio <= dynamic_force_tolerance .and. energy <= dynamic_energy_tolerance*max(energy_first, tiny(1.0_dp))) &
        exit
      if (iteration == stepper%iterations_allowed) then
        call set_error(error, 'the equilibrium iteration of the '//step_name(stepper)//' did not converge: after '// &
          integer_text(iteration)//' iterations the force residual is '//short_real(force_ratio)// &
          ' of the step''s forces (tolerance '//short_real(dynamic_force_tolerance)//') and the energy norm '// &
          short_real(energy/max(energy_first, tiny(1.0_dp)))//' of the first solve''s (tolerance '// &
          short_real(dynamic_energy_tolerance)//'); use a smaller DT, or more ITERATIONS= on the ANALYSIS card')
        return
      end if
      if (iteration > 1 .and. .not. stepper%full_newton) then   ! Aitken's acceleration (Irons and Tuck 1969)
        difference = stepper%correction - previous
        denominator = dot_product(difference, difference)
        if (denominator > 0.0_dp) relaxation = -relaxation*dot_product(previous, difference)/denominator
      end if
      previous = stepper%correction
      taken = relaxation*stepper%correction
      stepper%solution = stepper%solution + taken
    end do
    if (yielded > 0 .or. predicted) then
      stepper%iterations = stepper%iterations + iteration
      stepper%iterations_max = max(stepper%iterations_max, iteration)
      stepper%iterated_solves = stepper%iterated_solves + 1
    end if
    if (yielded > 0) then
      stepper%plastic_correction = stepper%solution - linear
    else if (allocated(stepper%plastic_correction)) then
      deallocate(stepper%plastic_correction)
    end if
    end associate
  end subroutine equilibrium_iterations

  !> NEWTON=FULL: the correction S_t d = r (r in stepper%correction on entry,
  !> d on return) with the consistent tangent of the current iterate,
  !> S_t = c M + (1 - alpha_f) K_t (K_t: plastic_point_tangents at the
  !> solve point, assembled by assemble_point_tangents), factored anew with the supports imposed and the held
  !> equations in its own capacitance system (zero values), as S~ is.
  subroutine tangent_correction(stepper, deck, point, state, c, kept, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    type(solve_point_t), intent(in) :: point
    type(dynamic_state_t), intent(in) :: state
    real(dp), intent(in) :: c, kept
    type(error_t), allocatable, intent(inout) :: error
    integer :: info
    call timer_start(phase_assembly)
    if (.not. stepper%finite) then                 ! KINEMATICS LARGE: K_t(U) came with f(U) (finite_solve_point)
      if (.not. allocated(stepper%point_tangents)) allocate(stepper%point_tangents(4, 4, gauss_count, deck%mesh%nelem))
      call plastic_point_tangents(stepper%operators, deck%materials, deck%mesh%element_material, stepper%yield_limit, &
                                  stepper%solution, point%shear_h, point%bulk_h, state%stress, state%ebar, &
                                  stepper%point_tangents, stepper%history_h)   ! history_h: absent without memory
      call assemble_point_tangents(deck%mesh, stepper%operators%b, stepper%operators%weight, stepper%point_tangents, &
                                   stepper%tangent)
    end if
    stepper%tangent%ab = kept*stepper%tangent%ab
    stepper%tangent%ab(1, :) = stepper%tangent%ab(1, :) + c*stepper%mass
    ! A supported equation keeps its diagonal only to hold its value: the stress term of a finite deformation
    ! may make it negative, which Cholesky would refuse; its magnitude holds the value as well.
    if (stepper%finite) where (stepper%supports) stepper%tangent%ab(1, :) = abs(stepper%tangent%ab(1, :))
    call timer_stop(phase_assembly)
    call timer_start(phase_factorization)
    call factor_compute(stepper%tangent_factor, stepper%tangent, stepper%supports, info, stepper%solver)
    stepper%tangent_factorizations = stepper%tangent_factorizations + 1
    if (info == 0) then
      call capacitance_reset(stepper%tangent_capacitance, stepper%tangent_factor%n)
      if (stepper%contact_on) call capacitance_set(stepper%tangent_capacitance, stepper%tangent_factor, &
                                                   stepper%held .and. .not. stepper%supports, info, error)
    end if
    call timer_stop(phase_factorization)
    if (allocated(error)) return
    if (info /= 0) then
      call set_error(error, 'the consistent tangent of the '//step_name(stepper)//' is not positive definite (equation '// &
        integer_text(abs(info))//'): the flesh softens faster than the step can follow; use NEWTON=MODIFIED or a '// &
        'smaller DT')
      return
    end if
    call held_correction(stepper, stepper%tangent, stepper%tangent_factor, stepper%tangent_capacitance, error)
  end subroutine tangent_correction

  !> The correction d of `matrix` d = r (r in stepper%correction on entry, d
  !> on return) on its factor, the supports and the held equations kept where
  !> they are (zero values; the held ones by the capacitance system).
  subroutine held_correction(stepper, matrix, factor, capacitance, error)
    type(stepper_t), intent(inout) :: stepper
    type(band_matrix_t), intent(in) :: matrix
    type(factor_t), intent(in) :: factor
    type(capacitance_t), intent(inout) :: capacitance    !< capacitance_apply keeps its multipliers
    type(error_t), allocatable, intent(inout) :: error
    integer :: status
    call band_constrain_rhs(matrix, stepper%supports, stepper%no_values, stepper%correction)
    call timer_start(phase_solve)
    call factor_solve(factor, stepper%correction, status)
    call timer_stop(phase_solve)
    if (status /= 0) then
      call set_error(error, solve_failure_text(status))
      return
    end if
    if (stepper%contact_on) call capacitance_apply(capacitance, stepper%no_values, stepper%correction)
  end subroutine held_correction

  !> The residual of the free equations once the held ones are eliminated:
  !> a body equation c held on a PAD's surface, u_c = sum_k w_k u_(p_k) (+ the
  !> gap), passes its residual to its partners, r_(p_k) + w_k r_c (the
  !> reduced system the capacitance solve answers), and keeps none; on the
  !> rigid plate (no partners) the residual itself. Compared on the free
  !> equations only, where the supports and held rows carry reactions.
  pure function reduced_residual(stepper, residual) result(reduced)
    type(stepper_t), intent(in) :: stepper
    real(dp), intent(in) :: residual(:)
    real(dp) :: reduced(size(residual))
    integer :: i, c, k
    reduced = residual
    if (.not. stepper%contact_on) return
    do i = 1, size(stepper%held_rows)
      c = stepper%held_rows(i)
      if (stepper%supports(c)) cycle
      do k = 1, 2
        associate (partner => stepper%contact%partner(k, c))
        if (partner > 0) reduced(partner) = reduced(partner) + stepper%contact%weight(k, c)*residual(c)
        end associate
      end do
    end do
  end function reduced_residual

  !> The stresses at the solve point t + h from the start state and dU
  !> (stepper%solution) with the moduli and history stress over h, the
  !> plastic points returned (visco2d_plastic_step): into stress_solve,
  !> increments_solve, internal_solve, ebar_solve, plastic_solve; `yielded`
  !> the Gauss points that yielded.
  subroutine plastic_solve_point(stepper, deck, point, state, yielded)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    type(solve_point_t), intent(in) :: point
    type(dynamic_state_t), intent(in) :: state
    integer, intent(out), optional :: yielded
    integer :: count
    if (.not. allocated(stepper%stress_solve)) allocate(stepper%stress_solve, stepper%strain_solve, &
                                                        stepper%increments_solve, mold=state%stress)
    if (.not. allocated(stepper%internal_solve)) allocate(stepper%internal_solve, mold=stepper%internal_next)
    call plastic_trial_stress(stepper%operators, deck%materials, deck%mesh%element_material, stepper%yield_limit, &
                              stepper%solution, point%shear_h, point%bulk_h, state%stress, state%ebar, &
                              stepper%increments_solve, stepper%stress_solve, stepper%internal_solve, stepper%ebar_solve, &
                              stepper%plastic_solve, count, stepper%history_h)   ! history_h: absent without memory
    if (present(yielded)) yielded = count
  end subroutine plastic_solve_point

  !> KINEMATICS LARGE: the bodies at the solve point, U_t + dU (dU in
  !> stepper%solution): f into internal_solve, the Cauchy stresses, the
  !> logarithmic strains into stress_solve, strain_solve (the lean
  !> elements' later, solve_point_state; with NEWTON=FULL also W into
  !> energy_solve and K_t(U) into stepper%tangent). An
  !> iterate that inverts an element takes back half of the last correction
  !> (`taken`, halved here; up to `halvings` times); the linear solve's
  !> iterate (iteration 1) cannot be taken back: an error.
  subroutine finite_solve_point(stepper, deck, state, h, iteration, taken, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    type(dynamic_state_t), intent(in) :: state
    real(dp), intent(in) :: h                      !< the solve interval (the histories advance over it)
    integer, intent(in) :: iteration
    real(dp), intent(inout) :: taken(:)
    type(error_t), allocatable, intent(inout) :: error
    integer, parameter :: halvings = 20
    integer :: cut
    if (.not. allocated(stepper%stress_solve)) allocate(stepper%stress_solve, stepper%strain_solve, &
                                                        stepper%increments_solve, mold=state%stress)
    if (.not. allocated(stepper%internal_solve)) allocate(stepper%internal_solve, mold=stepper%internal_next)
    stepper%finite_memory%dt = h
    do cut = 0, halvings
      if (stepper%full_newton .and. stepper%relaxing) then   ! the histories only when kept (finite_assemble's note)
        call finite_assemble(deck%mesh, deck%materials, deck%settings, state%u + stepper%solution, &
                             stepper%internal_solve, stepper%stress_solve, stepper%strain_solve, stepper%energy_solve, &
                             stepper%inverted, stepper%tangent, stepper%finite_memory, state%finite_history, &
                             stepper%history_at_solve)
      else if (stepper%full_newton) then
        call finite_assemble(deck%mesh, deck%materials, deck%settings, state%u + stepper%solution, &
                             stepper%internal_solve, stepper%stress_solve, stepper%strain_solve, stepper%energy_solve, &
                             stepper%inverted, stepper%tangent)
      else if (stepper%relaxing) then                ! the lean elements' strains at the converged iterate
        call lean_forces(stepper%reference, deck%mesh, deck%materials, deck%settings, state%u + stepper%solution, &
                         stepper%internal_solve, stepper%stress_solve, inverted=stepper%inverted, &
                         gradient=stepper%gradient_solve, strain=stepper%strain_solve, memory=stepper%finite_memory, &
                         history=state%finite_history, next=stepper%history_at_solve)
      else
        call lean_forces(stepper%reference, deck%mesh, deck%materials, deck%settings, state%u + stepper%solution, &
                         stepper%internal_solve, stepper%stress_solve, inverted=stepper%inverted, &
                         gradient=stepper%gradient_solve, strain=stepper%strain_solve)
      end if
      if (stepper%inverted == 0) return
      if (iteration == 1 .or. cut == halvings) exit
      taken = 0.5_dp*taken
      stepper%solution = stepper%solution - taken
      stepper%halvings = stepper%halvings + 1
    end do
    call set_error(error, 'element '//integer_text(deck%mesh%element_id(stepper%inverted))//' inverts at the '// &
      'solve point (KINEMATICS LARGE, equilibrium iteration '//integer_text(iteration)//'): the deformation is '// &
      'beyond what this mesh can follow in one step; use a smaller DT or a finer mesh')
  end subroutine finite_solve_point

  !> What the iterated step is, for its messages.
  pure function step_name(stepper) result(name)
    type(stepper_t), intent(in) :: stepper
    character(:), allocatable :: name
    if (stepper%finite) then
      name = 'finite-deformation step'
    else
      name = 'plastic step'
    end if
  end function step_name

  !> The stresses, strains and (with memory) histories at the solve point
  !> t + h of row r, from the start state and the solution dU_h with the
  !> moduli and the history stress over h (eqs. [13], [14], [23], [24]):
  !> the state in which the integrator holds equilibrium, the one the plate
  !> reactions are taken in (solve_point_reactions); with a PLASTIC
  !> material strain_solve is the elastic strain (less the plastic strain),
  !> the one the stored energy reads. Call it before
  !> commit_substep (it reads the start state); into stepper%stress_solve,
  !> strain_solve, history_solve. For Wilson-theta this, not the state at
  !> t + dt, is free of the overshoot of the stiff modes that a node
  !> arrested on the plate in the step excites: its free neighbours start
  !> the step with the velocity the node was stopped from, and Wilson-theta
  !> answers an initial velocity v in a mode with omega dt >> 1 with a
  !> displacement (1 - 1/theta^2) v dt at t + dt (and -0.78 times it at each
  !> step after), against ~v/omega at t + h.
  subroutine solve_point_state(stepper, deck, r, state)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    type(dynamic_state_t), intent(in) :: state
    associate (point => stepper%points(r))
    if (.not. allocated(stepper%stress_solve)) allocate(stepper%stress_solve, stepper%strain_solve, &
                                                        stepper%increments_solve, mold=state%stress)
    if (.not. allocated(stepper%internal_solve)) allocate(stepper%internal_solve, mold=stepper%internal_next)
    if (stepper%finite) then                        ! finite_solve_point's last evaluation is at this solution
      if (.not. stepper%full_newton) call gradient_strains(stepper%reference, stepper%gradient_solve, stepper%strain_solve)
      return
    end if
    if (stepper%plastic) then                       ! the last evaluation of equilibrium_iterations is at this solution
      stepper%history_solve = state%history
      if (stepper%memory) call commit_history(deck%mesh%element_material, stepper%history_solve, point%over_h, &
                                              stepper%increments_solve - stepper%plastic_solve)
    else if (stepper%memory) then
      call operators_trial_stress(stepper%operators, stepper%solution, point%shear_h, point%bulk_h, state%stress, &
                                  stepper%increments_solve, stepper%stress_solve, stepper%internal_solve, &
                                  stepper%history_h)
      stepper%history_solve = state%history
      call commit_history(deck%mesh%element_material, stepper%history_solve, point%over_h, stepper%increments_solve)
    else
      call operators_trial_stress(stepper%operators, stepper%solution, point%shear_h, point%bulk_h, state%stress, &
                                  stepper%increments_solve, stepper%stress_solve, stepper%internal_solve)
    end if
    stepper%strain_solve = state%strain + stepper%increments_solve
    if (stepper%plastic) stepper%strain_solve = stepper%strain_solve - state%plastic_strain - stepper%plastic_solve
    end associate
  end subroutine solve_point_state

  !> The sub-step stands: strains, stresses (the trial stresses) and the
  !> histories (eq. [24], over the sub-step), then U'' += dU'', U' += dU',
  !> U += dU (eqs. [40]-[42]) and the forces at the sub-step's end.
  subroutine commit_substep(stepper, deck, r, state, t_next)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    type(dynamic_state_t), intent(inout) :: state
    real(dp), intent(in) :: t_next
    real(dp) :: volume_ratio_min, volume_ratio_max, stretch_min
    state%strain = state%strain + stepper%increments
    if (stepper%plastic) then                       ! the histories take the elastic part de - de_p (eq. [24])
      stepper%plastic_dissipation = stepper%plastic_dissipation + &
                                    plastic_work(stepper%operators, state%stress, stepper%trial, stepper%plastic_increments)
      call yield_limits(deck%materials, deck%mesh%element_material, stepper%trial_ebar, stepper%yield_limit, &
                        previous=state%ebar)
      state%ebar = stepper%trial_ebar
      state%plastic_strain = state%plastic_strain + stepper%plastic_increments
      if (stepper%memory) call commit_history(deck%mesh%element_material, state%history, &
                                              stepper%points(r)%over_length, stepper%increments - stepper%plastic_increments)
    else if (stepper%memory) then
      call commit_history(deck%mesh%element_material, state%history, stepper%points(r)%over_length, stepper%increments)
    end if
    state%stress = stepper%trial
    if (stepper%finite) then                        ! KINEMATICS LARGE: W, the histories and the extremes of the deformation
      state%strain_energy = stepper%energy_next
      if (stepper%relaxing) state%finite_history = stepper%history_next
      call strain_extremes(state%strain, volume_ratio_min, volume_ratio_max, stretch_min)
      stepper%volume_ratio_min = min(stepper%volume_ratio_min, volume_ratio_min)
      stepper%volume_ratio_max = max(stepper%volume_ratio_max, volume_ratio_max)
      stepper%stretch_min = min(stepper%stretch_min, stretch_min)
    end if
    state%a = state%a + stepper%da                                    ! eqs. [40]-[42]
    state%v = state%v + stepper%dv
    state%u = state%u + stepper%du
    state%load = stepper%load_next
    state%internal = stepper%internal_next
    state%reaction = stepper%reaction_next
    state%target = stepper%target_next
    state%t = t_next
  end subroutine commit_substep
end module visco2d_time_step
