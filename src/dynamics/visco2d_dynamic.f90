!> The dynamic extension: M U'' + S U = R (eq. [25]) stepped in time, by
!> default with the paper's Wilson-theta method (Bathe and Wilson 1976,
!> eqs. [26]-[42]), with the lumped mass of eq. [32] and the incremental
!> viscoelastic law of visco2d_viscoelastic; INTEGRATOR chooses another
!> member of the family (module visco2d_integrators). The static base does
!> not use this module.
!>
!> One Wilson-theta step from t to t + dt, tau = theta dt (the printed typos
!> corrected as in doc/equations.md: [26] is M dU'' + S dU = dR, [37]'s left
!> side is dU'', [38] is dU' = U''_t dt + (dt/2) dU''):
!>   S~ = S(mu_tau) + 6/tau^2 M                                        eq. [35]
!>   S~ dU_tau = R_tau - F(sigma_t + s0_tau) + M (6/tau U'_t + 2 U''_t)  eqs. [34], [36]
!>   dU''  = (6/tau^2 dU_tau - 6/tau U'_t - 3 U''_t)/theta                eq. [37]
!>   dU'   = U''_t dt + dt/2 dU''                                         eq. [38]
!>   dU    = U'_t dt + dt^2/2 U''_t + dt^2/6 dU''                         eq. [39]
!>   U, U', U'' += dU, dU', dU''                                          eqs. [40]-[42]
!> with R_tau = R_t + theta (R_{t+dt} - R_t) and the history stress s0 of
!> eq. [23] (over tau) as a pseudo-load; stresses and history are then
!> advanced over dt (eqs. [13], [14], [23], [24]). Each stage is a procedure
!> of visco2d_time_step; this module runs them in order (time_step), and
!> around them what is measured: the impact (visco2d_impact), the energy
!> books and the instability check (visco2d_energy_balance), the history rows,
!> snapshots and summary (visco2d_dynamic_record), the timers.
!>
!> S~ depends on dt and on the supports only: it is factored once per TIME
!> stage. The equations the plate holds go through a capacitance (Schur-
!> complement) system on that factor (module visco2d_capacitance), so a
!> change of the contact set costs one back-substitution per new equation,
!> not a refactorization.
!>
!> Contact (a PLATE card, module visco2d_contact): after the solve, a free
!> boundary node that went through the plate gets an adjusted-displacement
!> condition (its u_z puts it on the plate at the end of the (sub-)step;
!> theta times that at the solve point t + tau) and the same increment is
!> repeated with it held; from then on its held components have U'' = U' =
!> dU = 0. The kinetic energy those components had is lost in the impact of
!> the node on the plate: it is reported (contact_loss_J) and kept in the
!> energy balance.
!>
!> The run stops with an error located at the TIME card if a value is not
!> finite, or if kinetic + internal energy grows far beyond what can have
!> been put into the body: an unstable integration. No NaN and no blown-up
!> value reaches the results.
module visco2d_dynamic
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error, locate_error
  use visco2d_strings, only: integer_text, message_real
  use visco2d_deck, only: deck_t, total_steps, initial_velocity, stop_at_tend, stop_at_separation
  use visco2d_dynamic_cards, only: integrator_wilson
  use visco2d_element, only: gauss_count
  use visco2d_factor, only: factor_solve, solve_failure_text
  use visco2d_assembly, only: external_load, node_dof, prescribed_displacement, internal_force, nodal_field
  use visco2d_viscoelastic, only: viscoelastic_state_create
  use visco2d_solve_errors, only: singular_error, node_text
  use visco2d_field_summary, only: put_field_summary, put_probe_summary
  use visco2d_record, only: record_t, record_put, record_put_real, record_put_integer
  use visco2d_timers, only: timer_start, timer_stop, timers_enabled, timers_set_floor, timers_set_steps, &
                            phase_assembly, phase_factorization, phase_constitutive, phase_contact, &
                            phase_output, phase_step_loop
  use visco2d_progress, only: progress_step, progress_expect_end, progress_impact_end
  use visco2d_advice, only: deformation_warnings, largest_strain
  use visco2d_bruise, only: bruise_t, bruise_update, bruise_report, envelopes_wanted, bruise_plastic_field
  use visco2d_impact, only: impact_t, impact_start, impact_measure, impact_summary, impact_surface_stress
  use visco2d_integrators, only: mass_coefficient, energy_overshoot, stability_advice
  use visco2d_dynamic_state, only: dynamic_state_t
  use visco2d_plastic_step, only: residual_flattening
  use visco2d_finite_assembly, only: memory_points_create
  use visco2d_pad_mesh, only: body_nodes, body_elements
  use visco2d_time_step, only: stepper_t, contact_hold_t, stepper_create, effective_stiffness, factor_effective, &
                               effective_load, solve_supports, contact_repeat, commit_substep, solve_point_state
  use visco2d_energy_balance, only: energy_balance_t, energy_growth_limit, balance_start, balance_substep, balance_contact_loss, &
                                 balance_growth
  use visco2d_dynamic_record, only: kept_state_t, dynamic_log_t, log_create, log_row, log_snapshot, log_field_times, &
                                    keep_state, insert_kept_snapshot, stored_energy, centre_of_mass, put_end_summary, &
                                    warn_unwritten_fields
  use visco2d_body_mesh, only: contact_card_line, contact_card_name
  implicit none
  private

  public :: solve_dynamic, energy_growth_limit

  !> What a run measures beside the step: the energy books, the impact, the
  !> envelopes, the record's log and the states kept at the maxima.
  type :: measures_t
    type(energy_balance_t) :: book
    type(impact_t) :: impact
    type(bruise_t) :: bruise                 !< envelopes (BRUISE cards or OUTPUT ENVELOPES=YES only)
    type(dynamic_log_t) :: log
    type(kept_state_t) :: at_alpha_max, at_q_max
  end type measures_t

contains

  !> The dynamic analysis of a deck (ANALYSIS DYNAMIC): fills the record with
  !> the summary, one history row every OUTPUT EVERY= steps (step 0 and the
  !> last step always) and snapshots at t = 0, at the FIELDS= times and at the
  !> end (with a plate also at maximum deformation and at maximum pressure).
  !> `hold` (tests only): another way to impose the plate's held equations
  !> than the capacitance system (an extension of contact_hold_t).
  subroutine solve_dynamic(deck, record, error, hold)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    class(contact_hold_t), intent(in), optional :: hold
    type(stepper_t) :: stepper
    type(dynamic_state_t) :: state, start
    type(measures_t) :: measures
    integer :: stage, step, step_count
    real(dp) :: t_next, dt, stage_start, touch_fraction
    character(:), allocatable :: unstable

    call stepper_create(deck, stepper, hold)
    call initial_state(deck, stepper, state)
    associate (body_mass => merge(0.0_dp, stepper%mass, stepper%pad))    ! the body's, not a PAD's
    if (stepper%contact_on .and. deck%body%line > 0) then                ! a second BODY: its masses too
      call impact_start(deck, body_mass, state%a, measures%impact, merge(stepper%mass, 0.0_dp, stepper%pad), state%v)
    else if (stepper%contact_on) then
      call impact_start(deck, body_mass, state%a, measures%impact)
    end if
    call balance_start(measures%book, stepper%mass, state%v)
    call log_create(deck, body_mass, stepper%contact_on, record, measures%log)
    end associate
    step_count = 0
    call log_row(measures%log, deck, record, step_count, state, measures%book, &
                 stored_energy(deck, stepper%operators, state, stepper%memory), measures%impact)
    call log_snapshot(measures%log, deck, record, 'initial', step_count, state)
    call log_field_times(measures%log, deck, record, step_count, state, .false.)

    stage_start = 0.0_dp
    call timer_start(phase_step_loop)
    stages: do stage = 1, size(deck%stages)
      dt = deck%stages(stage)%dt
      call factor_stage(stepper, deck, stage, dt, measures%book, error)
      if (allocated(error)) return
      do step = 1, deck%stages(stage)%steps
        t_next = stage_start + step*dt
        if (step == deck%stages(stage)%steps) t_next = deck%stages(stage)%end_time
        call time_step(stepper, deck, state, start, t_next, measures, touch_fraction, unstable, error)
        if (allocated(error)) then                   ! a failed solve: at the TIME stage, with the step
          call locate_error(error, deck%cards%file, deck%stages(stage)%line, 'TIME', ' at step '// &
                            integer_text(step_count + 1)//' (t = '//message_real(t_next)//' s)')
          return
        end if
        if (allocated(unstable)) then
          call unstable_error(stepper, deck, stage, step_count, start%t, dt, unstable, error)
          return
        end if
        step_count = step_count + 1
        call measure_step(stepper, deck, record, state, start, step_count, dt, touch_fraction, measures)
        if (measures%impact%stopped) exit stages
      end do
      stage_start = deck%stages(stage)%end_time
    end do stages
    call timer_stop(phase_step_loop)
    call timers_set_steps(step_count)
    if (timers_enabled()) then
      call measure_floor(stepper, error)
      if (allocated(error)) then
        call locate_error(error, deck%cards%file, card='TIME', where=' (measuring the solve time for --timing)')
        return
      end if
    end if
    call log_snapshot(measures%log, deck, record, 'final', step_count, state)
    call warn_unwritten_fields(measures%log, deck, record, state%t)
    call put_summary(stepper, deck, record, state, step_count, measures, error)
    if (allocated(error)) call locate_error(error, deck%cards%file, card='TIME', where=' (after the last step)')
  end subroutine solve_dynamic

  !> The body's nodal displacements (2, body nodes) of a vector in band order:
  !> the field keys are the body's, not a PAD's.
  function body_displacement(deck, u) result(displacement)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: u(:)
    real(dp), allocatable :: displacement(:, :)
    displacement = nodal_field(deck%mesh, u)
    displacement = displacement(:, :body_nodes(deck))
  end function body_displacement

  !> The state at t = 0: u = 0, the INITIAL / DROP velocity on the free
  !> equations, and the acceleration from equilibrium M a = R(0) + G - F(0)
  !> unless INITIAL gives it; no stress, and the Prony histories at 0.
  subroutine initial_state(deck, stepper, state)
    type(deck_t), intent(in) :: deck
    type(stepper_t), intent(in) :: stepper
    type(dynamic_state_t), intent(out) :: state
    integer :: k, n
    n = 2*deck%mesh%nnode
    if (stepper%memory) call viscoelastic_state_create(deck%materials, deck%mesh%element_material, state%history)
    if (stepper%relaxing) state%finite_history = memory_points_create(deck%mesh, stepper%finite_memory)
    allocate(state%stress(4, gauss_count, deck%mesh%nelem), state%strain(4, gauss_count, deck%mesh%nelem))
    state%stress = 0.0_dp
    state%strain = 0.0_dp
    if (stepper%plastic) then
      allocate(state%ebar(gauss_count, deck%mesh%nelem), state%plastic_strain(4, gauss_count, deck%mesh%nelem))
      state%ebar = 0.0_dp
      state%plastic_strain = 0.0_dp
    end if
    allocate(state%u(n), state%v(n))
    state%t = 0.0_dp
    state%u = 0.0_dp
    associate (velocity => initial_velocity(deck))
    state%v(1::2) = velocity(1)
    state%v(2::2) = velocity(2)
    end associate
    state%v = merge(0.0_dp, state%v, stepper%fixed .or. stepper%pad)   ! a PAD starts at rest
    if (deck%body%line > 0) state%v(2::2) = merge(deck%body%velocity, state%v(2::2), &   ! a second BODY at its VZ
                                                  stepper%pad(2::2) .and. .not. stepper%fixed(2::2))
    state%internal = internal_force(deck%mesh, deck%settings, state%stress)
    state%load = external_load(deck%mesh, deck%settings, deck%loads, 0.0_dp)
    state%a = (state%load + stepper%gravity - state%internal)/stepper%mass
    do k = 1, 2
      if (deck%dynamics%acceleration_given(k)) state%a(k::2) = deck%dynamics%acceleration(k)
    end do
    state%a = merge(0.0_dp, state%a, stepper%fixed .or. stepper%pad)
    state%target = prescribed_displacement(deck%mesh, deck%loads, 0.0_dp)
    state%reaction = merge(stepper%mass*state%a + state%internal - state%load - stepper%gravity, 0.0_dp, stepper%fixed)
  end subroutine initial_state

  !> Every row's S~ (eq. [35]) for the time step dt of a TIME stage, factored;
  !> also the energy bound of the instability check, widened by the
  !> integrator's overshoot for the highest frequency of the mesh, bounded by
  !> Gershgorin's theorem: omega_max^2 <= max_i sum_j |S_ij|/m_i.
  subroutine factor_stage(stepper, deck, stage, dt, book, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: stage
    real(dp), intent(in) :: dt
    type(energy_balance_t), intent(inout) :: book
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: row_sum(size(stepper%mass)), omega_max
    integer :: r, info
    do r = 1, size(stepper%points)
      call timer_start(phase_assembly)
      call effective_stiffness(stepper, deck, r, dt, row_sum)
      call timer_stop(phase_assembly)
      if (r == 1) then
        omega_max = sqrt(maxval(merge(row_sum/stepper%mass, 0.0_dp, .not. stepper%supports)))
        book%growth_limit = energy_growth_limit*energy_overshoot(stepper%integrator, omega_max, dt)
      end if
      call timer_start(phase_factorization)
      call factor_effective(stepper, r, info, error)
      call timer_stop(phase_factorization)
      if (allocated(error)) then
        call locate_error(error, deck%cards%file, deck%stages(stage)%line, 'TIME', ' (factoring the effective '// &
                          'stiffness of TIME stage '//integer_text(stage)//')')
        return
      else if (info > 0) then
        call effective_singular(stepper, deck, stage, r, dt, info, error)
        return
      else if (info < 0) then
        call set_error(error, 'the contact capacitance matrix is not positive definite (equation '// &
          integer_text(-info)//' of the held set)', file=deck%cards%file, line=contact_card_line(deck, .false.), &
        card=contact_card_name(deck, .false.))
        return
      end if
    end do
  end subroutine factor_stage

  !> S~ = S + c M with a positive lumped mass is positive definite in exact
  !> arithmetic: it fails only when the mass term is lost in round-off
  !> against S (a DT far too large, and a body free to move), or when S
  !> itself is not positive (a modulus). Located at the TIME card when the
  !> mass term is below round-off of the diagonal, else at the card of an
  !> element at the failing node.
  subroutine effective_singular(stepper, deck, stage, r, dt, equation, error)
    type(stepper_t), intent(in) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: stage, r, equation
    real(dp), intent(in) :: dt
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: mass_term, diagonal
    character(:), allocatable :: name, term
    associate (point => stepper%points(r))
    if (stepper%integrator%kind == integrator_wilson) then
      name = 'S + 6/(theta dt)^2 M'
      term = '6/(theta DT)^2 M'
    else
      name = 'S + c M of '//stepper%integrator%label//' (c = '//message_real(mass_coefficient(point%row, point%h))//' 1/s^2)'
      term = 'c M'
    end if
    mass_term = mass_coefficient(point%row, point%h)*minval(stepper%mass, mask=.not. stepper%supports)
    diagonal = maxval(abs(point%effective%ab(1, :)))
    if (.not. (mass_term > epsilon(1.0_dp)*diagonal)) then
      call set_error(error, 'the effective stiffness '//name//' is not positive definite'// &
        node_text(deck%mesh, equation)//': with DT = '//message_real(dt)//' s the mass term '//term//' ('// &
        message_real(mass_term)//') is lost in round-off against S (diagonal up to '//message_real(diagonal)// &
        '), so a body free to move has no stiffness against that motion; use a DT of the order of the '// &
        'duration of the event', file=deck%cards%file, line=deck%stages(stage)%line, card='TIME')
    else
      call singular_error(deck%mesh, deck%source, equation, error)
      error%message = 'the effective stiffness '//name//' is not positive definite: '//error%message
    end if
    end associate
  end subroutine effective_singular

  !> One time step from state%t to t_next: each sub-step (row) of the
  !> integrator runs the stages of visco2d_time_step in order, and is booked
  !> in the energy balance and checked for instability. `start` keeps U and
  !> U' at the step's start; touch_fraction is the earliest touch of the
  !> plate in the step (0..1). An error here is an unstable integration
  !> (completed with the advice by the caller) or a contact failure.
  subroutine time_step(stepper, deck, state, start, t_next, measures, touch_fraction, what, error)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    type(dynamic_state_t), intent(inout) :: state, start
    real(dp), intent(in) :: t_next
    type(measures_t), intent(inout) :: measures
    real(dp), intent(out) :: touch_fraction
    character(:), allocatable, intent(out) :: what   !< why the integration is unstable
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: t_end, offset, energy
    logical :: finite
    integer :: r
    start%t = state%t
    start%u = state%u
    start%v = state%v
    touch_fraction = 1.0_dp
    offset = 0.0_dp
    do r = 1, size(stepper%points)
      associate (point => stepper%points(r))
      t_end = t_next
      if (r < size(stepper%points)) t_end = state%t + point%length
      call effective_load(stepper, deck, r, state, start, t_end)                ! eq. [36]
      call solve_supports(stepper, r, state, error)                             ! eq. [34], supports only
      if (allocated(error)) return
      call contact_repeat(stepper, deck, r, state, start, finite, error)        ! the plate, eqs. [37]-[39], [13]-[23]
      if (allocated(error)) return
      if (.not. finite) then
        what = 'a displacement or acceleration is not finite (NaN or Inf)'
        return
      end if
      if (stepper%contact_on) then
        touch_fraction = min(touch_fraction, offset + point%row%fraction*stepper%touch_fraction)
        call impact_surface_stress(measures%impact, deck, stepper%contact, state%stress, stepper%solution, &
                                   point%over_h, stepper%memory, state%history)
        call balance_contact_loss(measures%book, deck, stepper%contact, stepper%mass, state%v)
      end if
      call balance_substep(measures%book, stepper%mass, stepper%gravity, stepper%supports, stepper%du, &
                        state%v + stepper%dv, state%load, stepper%load_next, state%internal, stepper%internal_next, &
                        state%reaction, stepper%reaction_next, energy)
      if (.not. ieee_is_finite(energy) .or. .not. all(ieee_is_finite(stepper%trial))) then
        what = 'the energy or a stress is not finite (NaN or Inf)'
        return
      end if
      call balance_growth(measures%book, energy, what)
      if (allocated(what)) return
      call end_substep(stepper, deck, r, state, t_end, measures)                ! eqs. [24], [40]-[42]
      offset = offset + point%row%fraction
      end associate
    end do
  end subroutine time_step

  !> The sub-step of row r committed (visco2d_time_step's commit_substep,
  !> eqs. [24], [40]-[42]) and the bruise envelopes updated. The envelopes
  !> take the state where the integrator holds equilibrium, as the plate
  !> reactions: t + theta dt for Wilson-theta (visco2d_time_step,
  !> solve_point_state), the sub-step's end otherwise. Timed as the
  !> constitutive update.
  subroutine end_substep(stepper, deck, r, state, t_end, measures)
    type(stepper_t), intent(inout) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: r
    type(dynamic_state_t), intent(inout) :: state
    real(dp), intent(in) :: t_end
    type(measures_t), intent(inout) :: measures
    real(dp) :: t_solve
    logical :: at_solve_point
    call timer_start(phase_constitutive)
    at_solve_point = stepper%points(r)%h /= stepper%points(r)%length .and. envelopes_wanted(deck)
    t_solve = state%t + stepper%points(r)%h
    if (at_solve_point) call solve_point_state(stepper, deck, r, state)
    call commit_substep(stepper, deck, r, state, t_end)                         ! eqs. [24], [40]-[42]
    if (.not. envelopes_wanted(deck)) then  ! no envelope kept (a PLASTIC run's plastic strain is its final ebar)
      call timer_stop(phase_constitutive)
      return
    end if
    if (at_solve_point) then              ! ebar_solve: absent (unallocated) without a PLASTIC material
      call bruise_update(measures%bruise, deck, t_solve, stepper%stress_solve, stepper%strain_solve, &
                         stepper%history_solve, stepper%ebar_solve)
    else if (stepper%plastic) then        ! the elastic strain, and ebar
      call bruise_update(measures%bruise, deck, t_end, state%stress, state%strain - state%plastic_strain, &
                         state%history, state%ebar)
    else
      call bruise_update(measures%bruise, deck, t_end, state%stress, state%strain, state%history)
    end if
    call timer_stop(phase_constitutive)
  end subroutine end_substep

  !> The measures after a step: the impact (plate reactions at the solve
  !> point, see visco2d_time_step) and the states at its maxima, the
  !> progress line, the history row and the FIELDS= snapshots.
  subroutine measure_step(stepper, deck, record, state, start, step_count, dt, touch_fraction, measures)
    type(stepper_t), intent(in) :: stepper
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(dynamic_state_t), intent(in) :: state, start
    integer, intent(in) :: step_count
    real(dp), intent(in) :: dt, touch_fraction
    type(measures_t), intent(inout) :: measures
    logical :: new_alpha_max, new_q_max
    real(dp) :: cm(3), cm_start(2)
    associate (impact => measures%impact, log => measures%log)
    call timer_start(phase_contact)
    if (stepper%contact_on) then
      cm = [centre_of_mass(log, state%u), centre_of_mass(log, state%v), centre_of_mass(log, state%a)]
      if (size(stepper%points) == 1) then          ! the arithmetic of the one-row integrators, as it always was
        cm_start = [centre_of_mass(log, state%u - stepper%du), centre_of_mass(log, state%v - stepper%dv)]
      else
        cm_start = [centre_of_mass(log, start%u), centre_of_mass(log, start%v)]
      end if
      call impact_measure(impact, deck, stepper%contact, state%t, dt, touch_fraction, cm, cm_start, &
                          stepper%reaction_solve, state%u, state%v, state%a, state%stress, new_alpha_max, new_q_max)
      if (impact%t_contact >= 0.0_dp .and. deck%stop_at /= stop_at_tend) &       ! a better end for the estimate
        call progress_expect_end(progress_impact_end(impact%t_contact, impact%alpha, cm(2), impact%v_cm_contact, &
                                                     deck%stop_at == stop_at_separation))
      if (new_alpha_max) call keep_state(measures%at_alpha_max, step_count, state)
      if (new_q_max) call keep_state(measures%at_q_max, step_count, state)
    end if
    call timer_stop(phase_contact)
    call progress_step(step_count, state%t, merge(1.0e3_dp*impact%alpha, -1.0_dp, impact%t_contact >= 0.0_dp))
    call timer_start(phase_output)
    if (mod(step_count, deck%output%every) == 0 .or. step_count == total_steps(deck) .or. impact%stopped) &
      call log_row(log, deck, record, step_count, state, measures%book, &
                   stored_energy(deck, stepper%operators, state, stepper%memory), impact)
    call log_field_times(log, deck, record, step_count, state, .true.)
    call timer_stop(phase_output)
    end associate
  end subroutine measure_step

  !> The floor of the step loop for `--timing`: the seconds of one
  !> back-substitution with the run's factor (the best of a few repeats).
  subroutine measure_floor(stepper, error)
    type(stepper_t), intent(in) :: stepper
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: rhs(size(stepper%effective_load))
    integer(int64) :: start, finish, rate
    real(dp) :: best
    integer :: repeat, status
    best = huge(1.0_dp)
    call system_clock(count_rate=rate)
    do repeat = 1, 5
      rhs = stepper%effective_load
      call system_clock(start)
      call factor_solve(stepper%points(1)%factor, rhs, status)
      call system_clock(finish)
      if (status /= 0) then
        call set_error(error, solve_failure_text(status))
        return
      end if
      best = min(best, real(finish - start, dp)/real(rate, dp))
    end do
    call timers_set_floor(best)
  end subroutine measure_floor

  !> Stop the run: the integration has become unstable in the step from t
  !> (`what`: the symptom); the advice names the integrator's stability condition.
  subroutine unstable_error(stepper, deck, stage, step_count, t, dt, what, error)
    type(stepper_t), intent(in) :: stepper
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: stage, step_count
    real(dp), intent(in) :: t, dt
    character(*), intent(in) :: what
    type(error_t), allocatable, intent(out) :: error
    call set_error(error, 'the time integration is unstable at step '//integer_text(step_count + 1)//' (t = '// &
      message_real(t + dt)//' s, DT = '//message_real(dt)//' s): '//what//'; '//stability_advice(stepper%integrator)// &
      '. No results were written.', file=deck%cards%file, line=deck%stages(stage)%line, card='TIME')
  end subroutine unstable_error

  !> The summary keys of the run: counts, the end state and energies, the
  !> impact (with the snapshots at its maxima), envelopes, small-strain
  !> warnings, the field and probe keys.
  subroutine put_summary(stepper, deck, record, state, step_count, measures, error)
    type(stepper_t), intent(in) :: stepper
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(dynamic_state_t), intent(in) :: state
    integer, intent(in) :: step_count
    type(measures_t), intent(in) :: measures
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, history_values
    associate (mesh => deck%mesh, at_alpha_max => measures%at_alpha_max, log => measures%log)
    call record_put_integer(record, 'steps', step_count)
    ! The paper's Wilson-theta is named by its theta key (as it always was);
    ! any other integrator by its label, e.g. 'NEWMARK BETA=0.25 GAMMA=0.5'.
    if (stepper%integrator%kind == integrator_wilson) then
      call record_put_real(record, 'theta', deck%dynamics%theta)
    else
      call record_put(record, 'integrator', stepper%integrator%label)
    end if
    call record_put_integer(record, 'factorizations', stepper%factorizations)
    if (stepper%contact_on) then
      call record_put_integer(record, 'capacitance_columns', sum(stepper%points%capacitance%solves))
      call record_put_integer(record, 'capacitance_factorizations', sum(stepper%points%capacitance%factorizations))
    end if
    history_values = 0
    if (stepper%memory) history_values = size(state%history%history)
    call put_end_summary(log, deck, record, state, measures%book, &
                         stored_energy(deck, stepper%operators, state, stepper%memory), history_values)
    if (stepper%contact_on) then
      call impact_summary(measures%impact, deck, stepper%contact, record, log%basis_factor*log%body_mass, state%t)
      if (measures%impact%t_contact >= 0.0_dp) then                     ! the fields at the maxima
        call insert_kept_snapshot(log, deck, record, at_alpha_max, 'maximum deformation')
        call insert_kept_snapshot(log, deck, record, measures%at_q_max, 'maximum pressure')
      end if
    end if
    call bruise_report(measures%bruise, deck, record)
    if (stepper%plastic .and. .not. envelopes_wanted(deck)) call bruise_plastic_field(deck, state%ebar, record)
    if (stepper%plastic) call put_plastic_summary(stepper, deck, record, state, log%basis_factor, error)
    if (stepper%finite) call put_finite_summary(stepper, record)
    if (allocated(error)) return
    ! Beyond the small-strain model: the largest principal strain at the end
    ! and at maximum deformation, and the approach against the radius.
    associate (body => body_elements(deck))
    if (at_alpha_max%kept) then
      call deformation_warnings(deck, record, max(largest_strain(state%strain(:, :, :body)), &
                                                  largest_strain(at_alpha_max%strain(:, :, :body))), &
                                max(largest_strain(state%strain(:, :, body + 1:)), &
                                    largest_strain(at_alpha_max%strain(:, :, body + 1:))))
    else
      call deformation_warnings(deck, record, largest_strain(state%strain(:, :, :body)), &
                                largest_strain(state%strain(:, :, body + 1:)))
    end if
    end associate
    ! The field keys of an impact describe the impact: the state at maximum
    ! deformation; the end state (after the rebound, or at TEND) has its own
    ! end_ keys. Without an impact they describe the end state.
    if (at_alpha_max%kept) then
      call record_put(record, 'field_keys_at', 'maximum deformation')
      call put_field_summary(body_displacement(deck, at_alpha_max%u), at_alpha_max%stress(:, :, :body_elements(deck)), &
                             record)
      call put_field_summary(body_displacement(deck, state%u), state%stress(:, :, :body_elements(deck)), record, &
                             prefix='end_')
    else
      call put_field_summary(body_displacement(deck, state%u), state%stress(:, :, :body_elements(deck)), record)
    end if
    call put_probe_summary(deck%mesh, deck%probes, nodal_field(mesh, state%u), state%stress, record)
    do k = 1, size(deck%probes)
      associate (r => node_dof(mesh, deck%probes(k)%node, 1), z => node_dof(mesh, deck%probes(k)%node, 2))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_vr_m_s', state%v(r))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_vz_m_s', state%v(z))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_ar_m_s2', state%a(r))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_az_m_s2', state%a(z))
      end associate
    end do
    end associate
  end subroutine put_summary

  !> The keys of a run with a PLASTIC material (doc/outputs.md): the
  !> equilibrium iterations, the plastic dissipation (the trapezoidal
  !> 1/2 (s_n + s_n+1) : de_p over the steps), the largest equivalent plastic
  !> strain and the yielded volume (the Gauss points' volumes with ebar > 0),
  !> energies and volumes times `factor` (the whole body in axisymmetry); in
  !> axisymmetry the residual flattening along the axis (visco2d_plastic_step).
  subroutine put_plastic_summary(stepper, deck, record, state, factor, error)
    type(stepper_t), intent(in) :: stepper
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(dynamic_state_t), intent(in) :: state
    real(dp), intent(in) :: factor
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: shortening
    logical :: found
    call record_put_integer(record, 'equilibrium_iterations', stepper%iterations)
    call record_put_integer(record, 'equilibrium_iterations_max', stepper%iterations_max)
    call record_put_integer(record, 'plastic_solves', stepper%iterated_solves)
    if (stepper%full_newton) call record_put_integer(record, 'tangent_factorizations', stepper%tangent_factorizations)
    call record_put_real(record, 'plastic_dissipation_J', factor*stepper%plastic_dissipation)
    call record_put_real(record, 'equivalent_plastic_strain_max', maxval(state%ebar))
    call record_put_real(record, 'yielded_volume_m3', factor*sum(stepper%operators%weight, mask=state%ebar > 0.0_dp))
    call residual_flattening(deck, stepper%operators%b, stepper%operators%weight, state%plastic_strain, shortening, &
                             found, error)
    if (allocated(error)) return
    if (found) call record_put_real(record, 'residual_flattening_mm', 1.0e3_dp*shortening)
  end subroutine put_plastic_summary

  !> The keys of a run with KINEMATICS LARGE (doc/outputs.md): the
  !> equilibrium iterations of the steps, the corrections halved because they
  !> inverted an element, and the extremes of the deformation over the run
  !> (the least and largest volume ratio J, the least principal stretch).
  subroutine put_finite_summary(stepper, record)
    type(stepper_t), intent(in) :: stepper
    type(record_t), intent(inout) :: record
    call record_put_integer(record, 'equilibrium_iterations', stepper%iterations)
    call record_put_integer(record, 'equilibrium_iterations_max', stepper%iterations_max)
    if (stepper%full_newton) call record_put_integer(record, 'tangent_factorizations', stepper%tangent_factorizations)
    call record_put_integer(record, 'newton_halvings', stepper%halvings)
    call record_put_real(record, 'volume_ratio_min', stepper%volume_ratio_min)
    call record_put_real(record, 'volume_ratio_max', stepper%volume_ratio_max)
    call record_put_real(record, 'stretch_min', stepper%stretch_min)
  end subroutine put_finite_summary
end module visco2d_dynamic
