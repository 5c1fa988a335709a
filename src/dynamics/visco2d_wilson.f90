!> The dynamic extension: M U'' + S U = R (eq. [25]) stepped in time by the
!> Wilson-theta method (Bathe and Wilson 1976), eqs. [26]-[42], with the
!> lumped mass of eq. [32] and the incremental viscoelastic law of
!> visco2d_viscoelastic. The static base does not use this module.
!>
!> One step from t to t + dt, tau = theta dt (the printed typos corrected as
!> in doc/equations.md: [26] is M dU'' + S dU = dR, [37]'s left side is dU'',
!> [38] is dU' = U''_t dt + (dt/2) dU''):
!>   S~ = S(mu_tau) + 6/tau^2 M                                        eq. [35]
!>   S~ dU_tau = R_tau - F(sigma_t + s0_tau) + M (6/tau U'_t + 2 U''_t)  eqs. [34], [36]
!>   dU''  = (6/tau^2 dU_tau - 6/tau U'_t - 3 U''_t)/theta                eq. [37]
!>   dU'   = U''_t dt + dt/2 dU''                                         eq. [38]
!>   dU    = U'_t dt + dt^2/2 U''_t + dt^2/6 dU''                         eq. [39]
!>   U, U', U'' += dU, dU', dU''                                          eqs. [40]-[42]
!> with R_tau = R_t + theta (R_{t+dt} - R_t) and the history stress s0 of
!> eq. [23] (over tau) as a pseudo-load. The right side of eq. [36] is
!> written in residual form: it equals theta dR + M (6/tau U'_t + 3 U''_t)
!> plus the out-of-balance force R_t - F_t - M U''_t, which eq. [36] drops.
!> Wilson-theta does not enforce equilibrium at t + dt, so that term is not
!> zero; keeping it makes the step exactly Bathe and Wilson's method (their
!> total form) and keeps round-off from drifting. Stresses and history are
!> then advanced over dt (eqs. [13], [14], [23], [24]).
!>
!> S~ depends on dt and on the supports only: it is factored once per TIME
!> stage. The equations the plate holds go through a capacitance (Schur-
!> complement) system on that factor (module visco2d_capacitance), so a
!> change of the contact set costs one back-substitution per new equation,
!> not a refactorization.
!>
!> Contact (a PLATE card, module visco2d_contact): after the solve, a free
!> boundary node that went through the plate gets an adjusted-displacement
!> condition (its u_z puts it on the plate at t + dt; theta times that at
!> t + tau) and the same increment is repeated with it held; from then
!> on its held components have U'' = U' = dU = 0. The kinetic energy those
!> components had is lost in the impact of the node on the plate: it is
!> reported (contact_loss_J) and kept in the energy balance. What the impact
!> reports (alpha, q, maxima, stop criteria) is measured by visco2d_impact.
!>
!> An energy balance is kept every step; the run stops with an error located
!> at the TIME card if a value is not finite, or if kinetic + internal energy
!> grows far beyond what can have been put into the body (the initial kinetic
!> energy and the positive work of loads, gravity and prescribed motions, not
!> the plate's reactions), or keeps growing past it step after step: an
!> unstable integration. No NaN and no blown-up value reaches the results.
module visco2d_wilson
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, whole_body_factor, energy_basis
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: itoa, gtoa, rtoa, short_real
  use visco2d_deck, only: deck_t, total_steps, initial_velocity, stop_at_tend, stop_at_separation
  use visco2d_dynamic_cards, only: theta_unconditional, integrator_wilson
  use visco2d_material, only: has_memory
  use visco2d_element, only: gauss_count
  use visco2d_operators, only: operators_t, operators_create, operators_trial_stress, operators_element_force
  use visco2d_banded, only: band_matrix_t, band_multiply_rows, band_factor, band_solve, band_constrain_matrix, &
                            band_constrain_rhs
  use visco2d_assembly, only: assemble_stiffness, external_load, support_mask, node_dof, &
                              prescribed_displacement, internal_force, scatter_add, lumped_mass, gravity_load, nodal_field
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients, viscoelastic_state_t, &
                                  viscoelastic_state_create, element_terms, deviatoric_part, history_stress, &
                                  update_history
  use visco2d_static, only: singular_error, node_text, node_corners, corner_stress, put_field_summary, &
                            put_probe_summary, set_snapshot_stress
  use visco2d_record, only: record_t, snapshot_t, record_put, record_put_real, record_put_integer, &
                            history_define, history_append, record_add_snapshot, record_insert_snapshot
  use visco2d_contact, only: contact_t, contact_create, contact_held_dofs, contact_begin_increment, &
                             contact_search, contact_gap
  use visco2d_timers, only: timer_start, timer_stop, timers_enabled, timers_set_floor, timers_set_steps, &
                            phase_assembly, phase_factorization, phase_solve, phase_constitutive, phase_contact, &
                            phase_output, phase_step_loop
  use visco2d_capacitance, only: capacitance_t, capacitance_reset, capacitance_set, capacitance_apply
  use visco2d_progress, only: progress_step, progress_expect_end, progress_impact_end
  use visco2d_advice, only: deformation_warnings, largest_strain
  use visco2d_bruise, only: bruise_t, bruise_update, bruise_report
  use visco2d_impact, only: impact_t, impact_start, impact_measure, impact_summary, impact_columns, impact_row, &
                            impact_surface_stress
  implicit none
  private

  public :: solve_dynamic, energy_growth_limit

  !> The (corner, element) pairs at a probe node (node_corners).
  type :: corners_t
    integer, allocatable :: pairs(:, :)
  end type corners_t

  !> The state at a running maximum, kept as plain copies (no conversion per
  !> step): it becomes a snapshot once, at the end of the run.
  type :: kept_state_t
    logical :: kept = .false.
    integer :: step = 0
    real(dp) :: time = 0.0_dp
    real(dp), allocatable :: u(:), v(:), a(:), stress(:, :, :), strain(:, :, :)
  end type kept_state_t

  !> The run stops as unstable when kinetic + internal energy exceeds this
  !> multiple of the energy that can have been put into the body: the initial
  !> kinetic energy plus the positive work of loads, gravity and prescribed
  !> (FIX) motions, step by step. The plate's reactions are not counted: a
  !> rigid fixed plate does no positive work on the body, so a diverging
  !> solution cannot raise the bound through them. The multiple is widened by
  !> Wilson-theta's transient overshoot (see `factor_for`).
  real(dp), parameter :: energy_growth_limit = 100.0_dp

  !> The growth-rate test: the run also stops when the energy in excess of that
  !> input has grown by at least `growth_rate_limit` in each of the last
  !> `growth_window` steps and has passed the input itself (a stable step
  !> cannot keep raising it: its spectral radius is below 1, and a first-step
  !> overshoot decays after one or two steps).
  integer, parameter :: growth_window = 3
  real(dp), parameter :: growth_rate_limit = 1.5_dp

contains

  !> The dynamic analysis of a deck (ANALYSIS DYNAMIC): fills the record with
  !> the summary, one history row every OUTPUT EVERY= steps (step 0 and the
  !> last step always) and snapshots at t = 0, at the FIELDS= times and at the
  !> end (with a plate also at maximum deformation and at maximum pressure).
  !> `refactor_contact` (tests only): impose contact by refactoring S~ with
  !> the held equations eliminated, instead of the capacitance system.
  subroutine solve_dynamic(deck, record, error, refactor_contact)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: refactor_contact
    type(capacitance_t) :: capacitance
    type(operators_t) :: operators
    logical :: by_refactoring
    type(band_matrix_t) :: effective, factor
    type(step_coefficients_t), allocatable :: over_tau(:), over_dt(:)
    type(viscoelastic_state_t) :: state
    type(contact_t) :: contact
    type(impact_t) :: impact
    type(kept_state_t) :: at_alpha_max, at_q_max
    type(bruise_t) :: bruise                 !< envelopes (BRUISE cards or OUTPUT ENVELOPES=YES only)
    type(corners_t), allocatable :: probe_corners(:)
    real(dp), allocatable :: row(:)
    real(dp), allocatable :: u(:), v(:), a(:), du(:), dv(:), da(:), rhs(:), base(:), prescribed(:), free(:)
    real(dp), allocatable :: mass(:), gravity(:), load(:), load_next(:), internal(:), internal_next(:)
    real(dp), allocatable :: reaction(:), reaction_next(:), target_now(:), target_next(:), reaction_tau(:)
    real(dp), allocatable :: stress(:, :, :), strain(:, :, :), trial(:, :, :), increments(:, :, :), history_dt(:, :, :)
    real(dp), allocatable :: shear_dt(:), bulk_dt(:)
    logical, allocatable :: fixed(:), supports(:), held(:)
    integer, allocatable :: held_rows(:)     !< the equations held by the plate (their reactions at t + tau)
    logical :: memory, contact_on
    integer :: step, stage, k, factorizations, step_count, next_field, width
    real(dp) :: t, t_next, dt, tau, theta, stage_start, body_mass
    real(dp) :: basis_factor   !< whole_body_factor: solver integrals to the reported energy_basis
    real(dp) :: kinetic, kinetic0, internal_work, load_work, support_work, gravity_work, contact_loss
    real(dp) :: positive_input            !< initial kinetic energy + positive work of loads, gravity, FIX motions
    real(dp) :: excess(0:growth_window)   !< kinetic + internal energy - positive_input, the last steps
    integer :: growth_steps               !< consecutive steps of excess growth by >= growth_rate_limit
    real(dp) :: stored, balance, balance_max, input_max, growth_limit, omega_max
    real(dp) :: touch_fraction

    if (deck%dynamics%integrator /= integrator_wilson) then
      call set_error(error, 'only INTEGRATOR WILSON is implemented so far', file=deck%cards%file, &
                     line=deck%dynamics%wilson_line, card='INTEGRATOR')
      return
    end if
    associate (mesh => deck%mesh, materials => deck%materials)
    by_refactoring = .false.
    if (present(refactor_contact)) by_refactoring = refactor_contact
    theta = deck%dynamics%theta
    memory = .false.
    do k = 1, size(materials)
      if (has_memory(materials(k)) .and. any(mesh%element_material == k)) memory = .true.
    end do
    if (memory) then
      call viscoelastic_state_create(materials, mesh%element_material, state)
      allocate(history_dt(4, gauss_count, mesh%nelem))
    end if
    contact_on = deck%plate%line > 0
    allocate(over_tau(size(materials)), over_dt(size(materials)))
    supports = support_mask(deck)
    fixed = supports
    allocate(held_rows(0))
    mass = lumped_mass(deck)                                   ! eq. [32], row sums
    body_mass = sum(mass(2::2))
    basis_factor = whole_body_factor(deck%geometry)
    gravity = gravity_load(deck)
    call operators_create(deck, operators)
    allocate(du(2*mesh%nnode), dv(2*mesh%nnode), da(2*mesh%nnode), prescribed(2*mesh%nnode), &
             internal_next(2*mesh%nnode), free(2*mesh%nnode))
    allocate(stress(4, gauss_count, mesh%nelem), strain(4, gauss_count, mesh%nelem), &
             trial(4, gauss_count, mesh%nelem), increments(4, gauss_count, mesh%nelem), &
             shear_dt(mesh%nelem), bulk_dt(mesh%nelem))
    stress = 0.0_dp
    strain = 0.0_dp
    factorizations = 0
    step_count = 0
    width = max(6, len(itoa(total_steps(deck))))
    contact_loss = 0.0_dp

    ! Initial state: u = 0, the INITIAL / DROP velocity on the free equations,
    ! and the acceleration from equilibrium M a = R(0) + G - F(0) unless INITIAL gives it.
    allocate(u(2*mesh%nnode), v(2*mesh%nnode), a(2*mesh%nnode))
    u = 0.0_dp
    associate (velocity => initial_velocity(deck))
    v(1::2) = velocity(1)
    v(2::2) = velocity(2)
    end associate
    v = merge(0.0_dp, v, fixed)
    internal = internal_force(deck, stress)
    load = external_load(deck, 0.0_dp)
    a = (load + gravity - internal)/mass
    do k = 1, 2
      if (deck%dynamics%acceleration_given(k)) a(k::2) = deck%dynamics%acceleration(k)
    end do
    a = merge(0.0_dp, a, fixed)
    target_now = prescribed_displacement(deck, 0.0_dp)
    reaction = merge(mass*a + internal - load - gravity, 0.0_dp, fixed)
    if (contact_on) call start_contact()

    kinetic0 = 0.5_dp*dot_product(mass, v**2)
    kinetic = kinetic0
    internal_work = 0.0_dp
    load_work = 0.0_dp
    support_work = 0.0_dp
    gravity_work = 0.0_dp
    positive_input = kinetic0
    excess = 0.0_dp
    growth_steps = 0
    balance_max = 0.0_dp
    input_max = kinetic0
    stored = 0.0_dp
    balance = 0.0_dp
    next_field = 1

    allocate(probe_corners(size(deck%probes)))
    do k = 1, size(deck%probes)
      probe_corners(k)%pairs = node_corners(mesh, deck%probes(k)%node)
    end do
    call define_history()
    t = 0.0_dp
    call append_row()
    call keep_snapshot('initial')
    call skip_field_times(0.0_dp)

    stage_start = 0.0_dp
    call timer_start(phase_step_loop)
    do stage = 1, size(deck%stages)
      dt = deck%stages(stage)%dt
      tau = theta*dt
      call factor_for(dt)
      if (allocated(error)) return
      do step = 1, deck%stages(stage)%steps
        t_next = stage_start + step*dt
        if (step == deck%stages(stage)%steps) t_next = deck%stages(stage)%end_time
        call advance()
        if (allocated(error)) return
        step_count = step_count + 1
        call timer_start(phase_contact)
        if (contact_on) call measure_impact()
        call timer_stop(phase_contact)
        call progress_step(step_count, t, merge(1.0e3_dp*impact%alpha, -1.0_dp, impact%t_contact >= 0.0_dp))
        call timer_start(phase_output)
        if (mod(step_count, deck%output%every) == 0 .or. step_count == total_steps(deck) .or. impact%stopped) &
          call append_row()
        if (next_field <= size(deck%output%field_times)) then
          if (t >= deck%output%field_times(next_field)*(1.0_dp - 1.0e-12_dp)) then
            call keep_snapshot('t = '//short_real(deck%output%field_times(next_field))//' s requested')
            call skip_field_times(t)
          end if
        end if
        call timer_stop(phase_output)
        if (impact%stopped) exit
      end do
      if (impact%stopped) exit
      stage_start = deck%stages(stage)%end_time
    end do
    call timer_stop(phase_step_loop)
    call timers_set_steps(step_count)
    if (timers_enabled()) call measure_floor()
    call keep_snapshot('final')

    stored = stored_energy()
    call record_put_integer(record, 'steps', step_count)
    call record_put_real(record, 'theta', theta)
    call record_put_integer(record, 'factorizations', factorizations)
    if (contact_on .and. .not. by_refactoring) then
      call record_put_integer(record, 'capacitance_columns', capacitance%solves)
      call record_put_integer(record, 'capacitance_factorizations', capacitance%factorizations)
    end if
    call record_put_real(record, 'time_end_s', t)
    ! Masses and energies on the energy_basis: the solver's per-radian integrals
    ! times 2 pi in axisymmetry (whole body), per metre of thickness in plane strain.
    call record_put(record, 'energy_basis', energy_basis(deck%geometry))
    call record_put_real(record, 'mass_kg', whole_body_mass())
    call record_put_real(record, 'body_mass_kg', whole_body_mass())
    call record_put_integer(record, 'history_values', history_values())
    call record_put_real(record, 'uz_cm_m', centre_of_mass(u))
    call record_put_real(record, 'vz_cm_m_s', centre_of_mass(v))
    call record_put_real(record, 'az_cm_m_s2', centre_of_mass(a))
    call record_put_real(record, 'kinetic_J', basis_factor*kinetic)
    call record_put_real(record, 'strain_energy_J', basis_factor*stored)
    call record_put_real(record, 'dissipated_J', basis_factor*(internal_work - stored))
    call record_put_real(record, 'external_work_J', basis_factor*(load_work + support_work))
    call record_put_real(record, 'gravity_work_J', basis_factor*gravity_work)
    call record_put_real(record, 'initial_kinetic_J', basis_factor*kinetic0)
    if (contact_on) call record_put_real(record, 'contact_loss_J', basis_factor*contact_loss)
    call record_put_real(record, 'balance_error_J', basis_factor*balance)
    call record_put_real(record, 'balance_error_max_J', basis_factor*balance_max)
    call record_put_real(record, 'balance_error_max_rel', balance_max/max(input_max, tiny(1.0_dp)))
    if (contact_on) then
      call impact_summary(impact, deck, contact, record, whole_body_mass(), t)
      if (impact%t_contact >= 0.0_dp) then                     ! the fields at the maxima
        call insert_maximum_snapshot(at_alpha_max, 'maximum deformation')
        call insert_maximum_snapshot(at_q_max, 'maximum pressure')
      end if
    end if
    call bruise_report(bruise, deck, record)
    ! Beyond the small-strain model: the largest principal strain at the end
    ! and at maximum deformation, and the approach against the radius.
    if (at_alpha_max%kept) then
      call deformation_warnings(deck, record, max(largest_strain(strain), largest_strain(at_alpha_max%strain)))
    else
      call deformation_warnings(deck, record, largest_strain(strain))
    end if
    ! The field keys of an impact describe the impact: the state at maximum
    ! deformation; the end state (after the rebound, or at TEND) has its own
    ! end_ keys. Without an impact they describe the end state.
    if (at_alpha_max%kept) then
      call record_put(record, 'field_keys_at', 'maximum deformation')
      call put_field_summary(nodal_field(deck%mesh, at_alpha_max%u), at_alpha_max%stress, record)
      call put_field_summary(nodal_field(deck%mesh, u), stress, record, prefix='end_')
    else
      call put_field_summary(nodal_field(deck%mesh, u), stress, record)
    end if
    call put_probe_summary(deck, nodal_field(deck%mesh, u), stress, record)
    do k = 1, size(deck%probes)
      associate (r => node_dof(mesh, deck%probes(k)%node, 1), z => node_dof(mesh, deck%probes(k)%node, 2))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_vr_m_s', v(r))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_vz_m_s', v(z))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_ar_m_s2', a(r))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_az_m_s2', a(z))
      end associate
    end do
    end associate

  contains

    !> S~ = S(mu over tau) + 6/tau^2 M (eq. [35]), constrained and factored;
    !> the step constants over tau (the solve) and over dt (the stress update).
    !> Also the energy limit of the instability check: a stable Wilson-theta
    !> step (theta >= 1.37, spectral radius < 1) can still raise the energy of
    !> a mode of frequency omega by about ((1 - 1/theta^2) omega dt)^2 before it
    !> decays, so the limit grows with that factor for the highest frequency,
    !> bounded by Gershgorin's theorem: omega_max^2 <= max_i sum_j |S_ij|/m_i.
    subroutine factor_for(dt)
      real(dp), intent(in) :: dt
      real(dp) :: row_sum(size(mass))
      integer :: m, i, j
      do m = 1, size(deck%materials)
        over_tau(m) = step_coefficients(deck%materials(m), theta*dt)
        over_dt(m) = step_coefficients(deck%materials(m), dt)
      end do
      shear_dt = over_dt(deck%mesh%element_material)%shear
      bulk_dt = over_dt(deck%mesh%element_material)%bulk
      call timer_start(phase_assembly)
      call assemble_stiffness(deck, over_tau(deck%mesh%element_material)%shear, &
                              over_tau(deck%mesh%element_material)%bulk, effective)
      call timer_stop(phase_assembly)
      row_sum = 0.0_dp
      do j = 1, effective%n
        do i = j, min(effective%n, j + effective%kd)
          row_sum(j) = row_sum(j) + abs(effective%ab(1 + i - j, j))
          if (i /= j) row_sum(i) = row_sum(i) + abs(effective%ab(1 + i - j, j))
        end do
      end do
      omega_max = sqrt(maxval(merge(row_sum/mass, 0.0_dp, .not. supports)))
      growth_limit = energy_growth_limit*max(1.0_dp, 2.0_dp*((1.0_dp - 1.0_dp/theta**2)*omega_max*dt)**2)
      effective%ab(1, :) = effective%ab(1, :) + 6.0_dp/(theta*dt)**2*mass
      call refactor()
    end subroutine factor_for

    !> Impose the supports on S~ and factor it (dpbtrf); the contact conditions
    !> then go through the capacitance system (hold_contact), or, with
    !> refactor_contact, are eliminated from S~ too.
    subroutine refactor()
      integer :: info
      call timer_start(phase_factorization)
      factor = effective
      if (by_refactoring) then
        call band_constrain_matrix(factor, fixed)
      else
        call band_constrain_matrix(factor, supports)
      end if
      call band_factor(factor, info)
      call timer_stop(phase_factorization)
      factorizations = factorizations + 1
      if (info > 0) then
        call effective_singular(info)
        return
      end if
      if (.not. by_refactoring) then
        call capacitance_reset(capacitance, factor%n)
        if (contact_on) call hold_contact()
      end if
    end subroutine refactor

    !> S~ = S + 6/(theta dt)^2 M with a positive lumped mass is positive
    !> definite in exact arithmetic: it fails only when the mass term is lost
    !> in round-off against S (a DT far too large, and a body free to move),
    !> or when S itself is not positive (a modulus). Located at the TIME card
    !> when the mass term is below round-off of the diagonal, else at the card
    !> of an element at the failing node.
    subroutine effective_singular(equation)
      integer, intent(in) :: equation
      real(dp) :: mass_term, diagonal
      mass_term = 6.0_dp/(theta*dt)**2*minval(mass, mask=.not. supports)
      diagonal = maxval(abs(effective%ab(1, :)))
      if (.not. (mass_term > epsilon(1.0_dp)*diagonal)) then
        call set_error(error, 'the effective stiffness S + 6/(theta dt)^2 M is not positive definite'// &
          node_text(deck, equation)//': with DT = '//rtoa(dt)//' s the mass term 6/(theta DT)^2 M ('// &
          rtoa(mass_term)//') is lost in round-off against S (diagonal up to '//rtoa(diagonal)// &
          '), so a body free to move has no stiffness against that motion; use a DT of the order of the '// &
          'duration of the event', file=deck%cards%file, line=deck%stages(stage)%line, card='TIME')
      else
        call singular_error(deck, equation, error)
        error%message = 'the effective stiffness S + 6/(theta dt)^2 M is not positive definite: '//error%message
      end if
    end subroutine effective_singular

    !> The contact set has changed: the held equations (not supports) into
    !> the capacitance system, or S~ refactored with them eliminated.
    subroutine hold_contact()
      integer :: info
      if (by_refactoring) then
        call refactor()
        return
      end if
      call timer_start(phase_factorization)
      call capacitance_set(capacitance, factor, held .and. .not. supports, info)
      call timer_stop(phase_factorization)
      if (info > 0) call set_error(error, 'the contact capacitance matrix is not positive definite '// &
        '(equation '//itoa(info)//' of the held set)', file=deck%cards%file, line=deck%plate%line, card='PLATE')
    end subroutine hold_contact

    !> One Wilson-theta step from t to t_next = t + dt; with a plate, repeated
    !> while the contact set changes.
    subroutine advance()
      integer :: e, g, nterm, slot, node, i
      real(dp) :: s0(4, gauss_count), deviatoric(4), volumetric, energy, fraction
      logical :: changed
      ! Loads and prescribed values at t + tau, linear in time (eq. [36]'s theta dR).
      load_next = external_load(deck, t_next)
      target_next = prescribed_displacement(deck, t_next)
      ! Right side of eqs. [34], [36] in residual form: R_tau - F(sigma_t + s0_tau) + M (6/tau v + 2 a).
      base = load + theta*(load_next - load) + gravity - internal + mass*(6.0_dp/tau*v + 2.0_dp*a)
      ! The history stress of eq. [23] in one pass: over tau as a pseudo-load
      ! on the solve (s0), over dt for the trial stresses (the same for every repeat).
      if (memory) then
        call timer_start(phase_constitutive)
        history_dt = 0.0_dp
        do e = 1, deck%mesh%nelem
          nterm = element_terms(state, e)
          if (nterm == 0) cycle
          associate (material => deck%materials(deck%mesh%element_material(e)), &
                     c_tau => over_tau(deck%mesh%element_material(e)), c_dt => over_dt(deck%mesh%element_material(e)))
          do g = 1, gauss_count
            slot = state%first(e) + (g - 1)*nterm
            associate (history => state%history(:, slot:slot + nterm - 1))
            s0(:, g) = history_stress(material, c_tau, history)
            history_dt(:, g, e) = history_stress(material, c_dt, history)
            end associate
          end do
          call scatter_add(deck%mesh, e, -operators_element_force(operators, e, s0), base)
          end associate
        end do
        call timer_stop(phase_constitutive)
      end if
      if (contact_on) then
        call contact_begin_increment(contact)
        touch_fraction = 1.0_dp
      end if

      ! dU_tau with the supports only, once per increment: a repeat after a
      ! contact change only changes the capacitance correction.
      prescribed = target_now + theta*(target_next - target_now) - u
      if (.not. by_refactoring) then
        call timer_start(phase_solve)
        free = base
        call band_constrain_rhs(effective, supports, prescribed, free)
        call band_solve(factor, free)                                 ! eq. [34] without contact
        call timer_stop(phase_solve)
      end if
      do
        if (contact_on) call adjusted_displacements(theta)
        call timer_start(phase_solve)
        if (by_refactoring) then
          rhs = base
          call band_constrain_rhs(effective, fixed, prescribed, rhs)
          call band_solve(factor, rhs)                                ! rhs <- dU_tau, eq. [34]
        else
          rhs = free
          if (contact_on) call capacitance_apply(capacitance, prescribed, rhs)   ! the held equations
        end if
        call timer_stop(phase_solve)
        ! The plate reactions at t + tau, where Wilson-theta holds equilibrium
        ! (the residual of eq. [34] on the held rows). Force, pressure and
        ! release use them: at t + dt a held node's reaction carries the stiff
        ! modes a contact event excites, which Wilson-theta damps only by its
        ! limit spectral radius (-0.78 per step at theta = 1.4), so it flips
        ! sign from step to step (spikes of 5x the impact force at nu = 0.4999,
        ! and release/recapture chatter with RELEASE=YES). Without the inertia
        ! M U''_tau of the held node itself: it is zero once a node is held, and
        ! in the step a node touches it is the impulse that stops the node's
        ! mass (reported as contact_loss_J), not a pressure on the plate.
        if (contact_on) then
          reaction_tau = 0.0_dp
          associate (p => held_rows)
          reaction_tau(p) = band_multiply_rows(effective, rhs, p) - base(p) &
            - mass(p)*(6.0_dp/tau**2*rhs(p) - 6.0_dp/tau*v(p) - 2.0_dp*a(p))
          end associate
        end if
        da = (6.0_dp/tau**2*rhs - 6.0_dp/tau*v - 3.0_dp*a)/theta        ! eq. [37]
        dv = a*dt + 0.5_dp*dt*da                                        ! eq. [38]
        du = v*dt + 0.5_dp*dt**2*a + dt**2/6.0_dp*da                    ! eq. [39]
        if (contact_on) then                                            ! held on the plate: U'' = U' = 0
          call adjusted_displacements(1.0_dp)
          du = merge(prescribed, du, held)
          dv = merge(-v, dv, held)
          da = merge(-a, da, held)
        end if
        if (.not. all(ieee_is_finite(da)) .or. .not. all(ieee_is_finite(du))) then
          call unstable('a displacement or acceleration is not finite (NaN or Inf)'); return
        end if

        ! Trial stresses over dt: eqs. [13], [14], [23] (the history is updated once the increment stands).
        call timer_start(phase_constitutive)
        if (memory) then
          call operators_trial_stress(operators, du, shear_dt, bulk_dt, stress, increments, trial, internal_next, &
                                      history_dt)
        else
          call operators_trial_stress(operators, du, shear_dt, bulk_dt, stress, increments, trial, internal_next)
        end if
        call timer_stop(phase_constitutive)
        reaction_next = merge(mass*(a + da) + internal_next - load_next - gravity, 0.0_dp, fixed)
        if (.not. contact_on) exit
        ! The contact search; a changed set repeats the increment (the paper's iteration).
        call timer_start(phase_contact)
        call contact_search(deck, contact, u, du, reaction_tau, changed, fraction)
        call timer_stop(phase_contact)
        if (.not. changed) exit
        touch_fraction = min(touch_fraction, fraction)
        held = contact_held_dofs(deck, contact)
        fixed = supports .or. held
        held_rows = pack([(i, i = 1, size(held))], held)
        call hold_contact()
        if (allocated(error)) return
      end do

      if (contact_on) call impact_surface_stress(impact, deck, contact, stress, rhs, over_tau, memory, state)
      ! The increment stands: strains, stresses and history (eq. [24]).
      call timer_start(phase_constitutive)
      do e = 1, deck%mesh%nelem
        strain(:, :, e) = strain(:, :, e) + increments(:, :, e)
        if (.not. memory) cycle
        nterm = element_terms(state, e)
        if (nterm == 0) cycle
        do g = 1, gauss_count
          slot = state%first(e) + (g - 1)*nterm
          call deviatoric_part(increments(:, g, e), deviatoric, volumetric)
          call update_history(over_dt(deck%mesh%element_material(e)), deviatoric, &
                              state%history(:, slot:slot + nterm - 1))
        end do
      end do
      stress = trial
      call bruise_update(bruise, deck, t_next, stress, strain, state)
      call timer_stop(phase_constitutive)
      if (contact_on) then                       ! the kinetic energy of the components stopped by the plate
        do i = 1, size(contact%candidates)
          node = contact%candidates(i)
          if (.not. contact%touched(node)) cycle
          associate (r => node_dof(deck%mesh, node, 1), z => node_dof(deck%mesh, node, 2))
          contact_loss = contact_loss + 0.5_dp*mass(z)*v(z)**2
          if (contact%stick) contact_loss = contact_loss + 0.5_dp*mass(r)*v(r)**2
          end associate
        end do
      end if
      a = a + da                                                      ! eqs. [40]-[42]
      v = v + dv
      u = u + du

      ! Energy balance: trapezoidal work of every force over du (exact for
      ! forces linear in u, as the elastic internal force is).
      internal_work = internal_work + 0.5_dp*dot_product(internal + internal_next, du)
      ! The work of the supports is that of the FIX supports only (prescribed
      ! motions, an input). The fixed rigid plate does no work: the kinetic
      ! energy of a node it stops is booked as contact_loss, and the
      ! trapezoidal reaction work of the step a node touches (its large
      ! reaction times its free travel to the plate) would be an artifact
      ! (26 % of the input at nu = 0.4999).
      associate (load_increment => 0.5_dp*dot_product(load + load_next, du), &
                 support_increment => 0.5_dp*sum(merge(reaction + reaction_next, 0.0_dp, supports)*du), &
                 gravity_increment => dot_product(gravity, du))
      load_work = load_work + load_increment
      support_work = support_work + support_increment
      gravity_work = gravity_work + gravity_increment
      positive_input = positive_input + max(0.0_dp, load_increment) + max(0.0_dp, support_increment) + &
                       max(0.0_dp, gravity_increment)
      end associate
      kinetic = 0.5_dp*dot_product(mass, v**2)
      balance = kinetic + internal_work + contact_loss - (kinetic0 + load_work + support_work + gravity_work)
      input_max = max(input_max, kinetic0 + abs(load_work + support_work + gravity_work))
      balance_max = max(balance_max, abs(balance))
      energy = kinetic + internal_work
      if (.not. ieee_is_finite(energy) .or. .not. all(ieee_is_finite(stress))) then
        call unstable('the energy or a stress is not finite (NaN or Inf)'); return
      end if
      call check_growth(energy)
      if (allocated(error)) return
      load = load_next
      internal = internal_next
      reaction = reaction_next
      target_now = target_next
      t = t_next
    end subroutine advance

    !> The instability test after a step (kinetic + internal energy `energy`):
    !> the bound energy_growth_limit (widened by the overshoot, factor_for)
    !> times the positive input, and the growth rate of the excess over it.
    subroutine check_growth(energy)
      real(dp), intent(in) :: energy
      excess(0:growth_window - 1) = excess(1:growth_window)
      excess(growth_window) = energy - positive_input
      if (excess(growth_window) >= growth_rate_limit*excess(growth_window - 1) .and. &
          excess(growth_window - 1) > 0.0_dp) then
        growth_steps = growth_steps + 1
      else
        growth_steps = 0
      end if
      if (energy > growth_limit*positive_input .and. energy > 0.0_dp) then
        call unstable('the kinetic + internal energy ('//gtoa(energy)//' J) has grown past '// &
          rtoa(growth_limit)//' times the energy put into the body ('//gtoa(positive_input)//' J: the initial '// &
          'kinetic energy and the positive work of loads, gravity and prescribed motions)')
      else if (growth_steps >= growth_window .and. excess(growth_window) > positive_input) then
        call unstable('the kinetic + internal energy ('//gtoa(energy)//' J) exceeds the energy put into the '// &
          'body ('//gtoa(positive_input)//' J) and has grown by '//rtoa(growth_rate_limit)//' or more in each of '// &
          'the last '//itoa(growth_window)//' steps (by '// &
          rtoa(excess(growth_window)/max(excess(0), tiny(1.0_dp)))//' in all)')
      end if
    end subroutine check_growth

    !> The floor of the step loop for `--timing`: the seconds of one dpbtrs
    !> back-substitution with the run's factor (the best of a few repeats).
    subroutine measure_floor()
      integer(int64) :: start, finish, rate
      real(dp) :: best
      integer :: repeat
      best = huge(1.0_dp)
      call system_clock(count_rate=rate)
      do repeat = 1, 5
        rhs = base
        call system_clock(start)
        call band_solve(factor, rhs)
        call system_clock(finish)
        best = min(best, real(finish - start, dp)/real(rate, dp))
      end do
      call timers_set_floor(best)
    end subroutine measure_floor

    !> The adjusted displacements of the contact conditions, into `prescribed`:
    !> a contact node's u_z goes to the plate over the increment (0 once it is
    !> there), u_r stays (STICK); `fraction` = theta gives the values at t + tau.
    !> Supports keep their own values (an axis node's u_r is 0 either way).
    subroutine adjusted_displacements(fraction)
      real(dp), intent(in) :: fraction
      integer :: i, node
      do i = 1, size(contact%candidates)
        node = contact%candidates(i)
        if (.not. contact%active(node)) cycle
        associate (r => node_dof(deck%mesh, node, 1), z => node_dof(deck%mesh, node, 2))
        if (.not. supports(z)) prescribed(z) = -fraction*contact_gap(deck, contact, u, node)
        if (contact%stick .and. .not. supports(r)) prescribed(r) = 0.0_dp
        end associate
      end do
    end subroutine adjusted_displacements

    !> The contact state and the impact measures at t = 0.
    subroutine start_contact()
      call contact_create(deck, contact)
      allocate(held(2*deck%mesh%nnode), reaction_tau(2*deck%mesh%nnode))
      held = .false.
      reaction_tau = 0.0_dp
      call impact_start(deck, mass, a, impact)
    end subroutine start_contact

    !> After a step: the impact measures (plate reactions at t + theta dt, see
    !> advance), and the fields at a new maximum of alpha or q, kept raw: their
    !> nodal stresses are recovered once, at the end (insert_maximum_snapshot).
    subroutine measure_impact()
      logical :: new_alpha_max, new_q_max
      real(dp) :: cm(3)
      cm = [centre_of_mass(u), centre_of_mass(v), centre_of_mass(a)]
      call impact_measure(impact, deck, contact, t, dt, touch_fraction, cm, &
                          [centre_of_mass(u - du), centre_of_mass(v - dv)], reaction_tau, u, v, a, stress, &
                          new_alpha_max, new_q_max)
      if (impact%t_contact >= 0.0_dp .and. deck%stop_at /= stop_at_tend) &       ! a better end for the estimate
        call progress_expect_end(progress_impact_end(impact%t_contact, impact%alpha, cm(2), impact%v_cm_contact, &
                                                     deck%stop_at == stop_at_separation))
      if (new_alpha_max) call keep_state(at_alpha_max)
      if (new_q_max) call keep_state(at_q_max)
    end subroutine measure_impact

    !> Copy the state now (the arrays are allocated once, at the first copy).
    subroutine keep_state(kept)
      type(kept_state_t), intent(inout) :: kept
      kept%kept = .true.
      kept%step = step_count
      kept%time = t
      kept%u = u
      kept%v = v
      kept%a = a
      kept%stress = stress
      kept%strain = strain
    end subroutine keep_state

    !> A kept state as a snapshot (nodal fields and stresses), inserted in time order.
    subroutine insert_maximum_snapshot(kept, label)
      type(kept_state_t), intent(in) :: kept
      character(*), intent(in) :: label
      type(snapshot_t) :: snapshot
      if (.not. kept%kept) return
      snapshot = fields_snapshot(label, kept%step, kept%time, kept%u, kept%v, kept%a, kept%stress)
      call record_insert_snapshot(record, snapshot)
    end subroutine insert_maximum_snapshot

    !> A snapshot named after its step: nodal displacement, velocity,
    !> acceleration and the stresses (Gauss and recovered nodal values).
    function fields_snapshot(label, at_step, time, u_now, v_now, a_now, stress_now) result(snapshot)
      character(*), intent(in) :: label
      integer, intent(in) :: at_step
      real(dp), intent(in) :: time, u_now(:), v_now(:), a_now(:), stress_now(:, :, :)
      type(snapshot_t) :: snapshot
      character(len=16) :: digits
      write(digits, '(i0.'//itoa(width)//')') at_step
      snapshot%name = 'step_'//trim(digits)
      snapshot%label = label
      snapshot%time = time
      snapshot%displacement = nodal_field(deck%mesh, u_now)
      snapshot%velocity = nodal_field(deck%mesh, v_now)
      snapshot%acceleration = nodal_field(deck%mesh, a_now)
      call set_snapshot_stress(deck%mesh, stress_now, snapshot)
    end function fields_snapshot

    !> Mass of the whole body, kg (2 pi times the mass per radian in axisymmetry).
    real(dp) function whole_body_mass()
      whole_body_mass = basis_factor*body_mass
    end function whole_body_mass

    !> Number of Prony history values allocated (0 without viscoelastic memory).
    integer function history_values()
      history_values = 0
      if (memory) history_values = size(state%history)
    end function history_values

    !> Stop the run: the integration has become unstable at time t + dt.
    subroutine unstable(what)
      character(*), intent(in) :: what
      character(:), allocatable :: advice
      if (theta < theta_unconditional) then
        advice = 'WILSON THETA = '//short_real(theta)//' is only conditionally stable: use THETA >= 1.37 '// &
          '(1.4 is usual) or a DT well below the shortest period of the mesh'
      else
        advice = 'check the material constants, the loads and DT'
      end if
      call set_error(error, 'the time integration is unstable at step '//itoa(step_count + 1)//' (t = '// &
        rtoa(t + dt)//' s, DT = '//rtoa(dt)//' s): '//what//'; '//advice//'. No results were written.', &
        file=deck%cards%file, line=deck%stages(stage)%line, card='TIME')
    end subroutine unstable

    !> Strain energy stored in the springs: per Gauss point
    !> K theta^2/2 + G_inf e:e + sum_m G_m C_m:C_m (C_m = the history of term m,
    !> whose spring carries s_m = 2 G_m C_m), times |J| r.
    real(dp) function stored_energy() result(energy)
      real(dp) :: deviatoric(4), volumetric, density
      integer :: e, g, m, nterm, slot
      energy = 0.0_dp
      do e = 1, deck%mesh%nelem
        associate (material => deck%materials(deck%mesh%element_material(e)))
        nterm = 0
        if (memory) nterm = element_terms(state, e)
        do g = 1, gauss_count
          call deviatoric_part(strain(:, g, e), deviatoric, volumetric)
          density = 0.5_dp*material%bulk*volumetric**2 + material%long_term_shear*contracted(deviatoric)
          do m = 1, nterm
            slot = state%first(e) + (g - 1)*nterm + m - 1
            density = density + material%prony_shear(m)*contracted(state%history(:, slot))
          end do
          energy = energy + operators%weight(g, e)*density
        end do
        end associate
      end do
    end function stored_energy

    !> e:e of a deviatoric strain in engineering form (gamma_rz = 2 e_rz).
    pure real(dp) function contracted(e)
      real(dp), intent(in) :: e(4)
      contracted = e(1)**2 + e(2)**2 + e(3)**2 + 0.5_dp*e(4)**2
    end function contracted

    !> Mass-weighted mean of the z components of a nodal vector (the centre of mass).
    real(dp) function centre_of_mass(vector)
      real(dp), intent(in) :: vector(:)
      centre_of_mass = dot_product(mass(2::2), vector(2::2))/body_mass
    end function centre_of_mass

    subroutine define_history()
      character(len=48), allocatable :: columns(:)
      integer :: p
      character(len=8), parameter :: probe_columns(10) = ['ur_m    ', 'uz_m    ', 'vr_m_s  ', 'vz_m_s  ', &
        'ar_m_s2 ', 'az_m_s2 ', 'sr_Pa   ', 'sz_Pa   ', 'st_Pa   ', 'trz_Pa  ']
      columns = [character(len=48) :: 'step', 't_s', 'max_displacement_m', 'uz_cm_m', 'vz_cm_m_s', &
                 'az_cm_m_s2', 'kinetic_J', 'strain_J', 'dissipated_J', 'external_work_J', 'gravity_work_J', &
                 'balance_error_J', 'reaction_r_N', 'reaction_z_N']
      if (contact_on) columns = [character(len=48) :: columns, impact_columns(), 'contact_loss_J']
      do p = 1, size(deck%probes)
        do k = 1, size(probe_columns)
          columns = [character(len=48) :: columns, deck%probes(p)%name//'_'//trim(probe_columns(k))]
        end do
      end do
      call history_define(record, columns, total_steps(deck)/deck%output%every + 2)
      allocate(row(size(columns)))
    end subroutine define_history

    !> One history row (the columns of define_history), into the row kept for it.
    subroutine append_row()
      integer :: p, node, first, columns_impact
      real(dp) :: largest
      stored = stored_energy()
      largest = 0.0_dp
      do node = 1, deck%mesh%nnode
        largest = max(largest, hypot(u(node_dof(deck%mesh, node, 1)), u(node_dof(deck%mesh, node, 2))))
      end do
      row(1:14) = [real(step_count, dp), t, largest, centre_of_mass(u), centre_of_mass(v), centre_of_mass(a), &
                   basis_factor*[kinetic, stored, internal_work - stored, load_work + support_work, gravity_work, &
                           balance, sum(reaction(1::2)), sum(reaction(2::2))]]
      first = 15
      ! t_ms and alpha_mm are filled in by impact_summary, once first contact is known.
      if (contact_on) then
        columns_impact = size(impact_columns())
        row(first:first + columns_impact - 1) = impact_row(impact)
        row(first + columns_impact) = basis_factor*contact_loss
        first = first + columns_impact + 1
      end if
      do p = 1, size(deck%probes)
        node = deck%probes(p)%node
        associate (r => node_dof(deck%mesh, node, 1), z => node_dof(deck%mesh, node, 2))
        row(first:first + 9) = [u(r), u(z), v(r), v(z), a(r), a(z), corner_stress(stress, probe_corners(p)%pairs)]
        end associate
        first = first + 10
      end do
      call history_append(record, row)
    end subroutine append_row

    !> Advance next_field past every requested time at or before `time`.
    subroutine skip_field_times(time)
      real(dp), intent(in) :: time
      do while (next_field <= size(deck%output%field_times))
        if (deck%output%field_times(next_field)*(1.0_dp - 1.0e-12_dp) > time) exit
        next_field = next_field + 1
      end do
    end subroutine skip_field_times

    subroutine keep_snapshot(label)
      character(*), intent(in) :: label
      if (allocated(record%snapshots)) then
        if (size(record%snapshots) > 0) then
          associate (last => record%snapshots(size(record%snapshots)))
          if (last%time == t) then                                     ! already kept at this step
            last%label = last%label//'; '//label
            return
          end if
          end associate
        end if
      end if
      call record_add_snapshot(record, snapshot_now(label))
    end subroutine keep_snapshot

    !> The fields now, as a snapshot named after the step.
    function snapshot_now(label) result(snapshot)
      character(*), intent(in) :: label
      type(snapshot_t) :: snapshot
      snapshot = fields_snapshot(label, step_count, t, u, v, a, stress)
    end function snapshot_now
  end subroutine solve_dynamic
end module visco2d_wilson
