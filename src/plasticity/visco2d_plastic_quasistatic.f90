!> ANALYSIS QUASISTATIC of a deck with a PLASTIC material: the legacy
!> program's time loop (visco2d_quasistatic: step 0 at t = 0 with dt = 0,
!> then every step of the TIME stages) with each step iterated to
!> equilibrium by full Newton with the consistent tangent, as the load
!> increments of visco2d_plastic_static are.
!>
!> Step n to time t with step length dt: the step's coefficients of every
!> material over dt (mu_n of eq. [21], J_m of eq. [22], K; dt = 0 at step 0:
!> mu = G(0)), the loads R(t) and the prescribed values at t from the deck's
!> curves and stages (as solve_quasistatic takes them). Newton iteration i
!> solves K_t du = R(t) - F(sigma(u)) (the prescribed values' increment in
!> the first iteration), K_t = sum_e sum_gp B^T C_gp B |J| r from the
!> tangents of the last evaluation; the first iteration's are those of the
!> step's start (u = u_n: every point's trial is its relaxed stress
!> sigma_n + s0, eq. [23], so an elastic step's first iteration is the
!> legacy solve S_n dU = R(t_n) - F(sigma_(n-1) + s0_n)). Every Gauss point
!> is updated from the step's start with the step's increment de:
!>  - a PLASTIC material: viscoplastic_update (visco2d_plasticity): the
!>    deviatoric trial s_n + s0 + 2 mu_n dev(de) (eqs. [13], [21], [23])
!>    returned to the yield surface, p_n + K tr(de) (eq. [14]), the Prony
!>    histories updated with the elastic part dev(de) - de_p (eq. [24]);
!>    its tangent the consistent one with mu_n in place of G;
!>  - any other material: the legacy update sigma_n + s0 + D(mu_n, K) de
!>    (eqs. [13], [14]) and the histories with dev(de) (eq. [24]); its
!>    tangent D(mu_n, K).
!> A step has converged when, as in the static increments,
!>   |r|  <= force_tolerance  max(|R(t)|, |F(u)|, F_run)   (free equations; F holds the reactions)
!>   |r . K_t^-1 r| <= energy_tolerance max(|du_1 . r_0|, |u . F(u)|, E_run)
!> hold, F_run and E_run the largest |R|, |F| and |u . F| of the steps
!> before: unlike a static increment, a step may barely move (a held strain
!> relaxing with a long time constant, a creep load held), and then the
!> first correction's energy is itself near round-off; and a step may end
!> near zero stress (an unloading bar crossing sigma = 0), where a
!> residual relative to its own small forces is round-off of the run's; after `settings%iterations` (ANALYSIS QUASISTATIC ITERATIONS=,
!> default 30) the error names the step, its time and both residuals (the
!> caller locates it at the stage's TIME card); nothing is written.
!>
!> Energies (per radian in axisymmetry; the keys on the energy basis): the
!> work of the loads and reactions W = sum 1/2 (P_(n-1) + P_n) . (u_n -
!> u_(n-1)) (P the load on the free equations, the reactions on the
!> supported ones; P_(-1) = 0, u_(-1) = 0); the stored energy of the springs
!> U = int (K theta^2/2 + G_inf e_e:e_e + sum_m G_m C_m:C_m) dV, e_e = e - e_p
!> the elastic deviatoric strain and C_m the history of term m (its spring
!> carries s_m = 2 G_m C_m); the plastic dissipation
!> D_p = sum int 1/2 (s_(n-1) + s_n) : de_p dV; the dashpots'
!> D_v = sum int sum_m 1/2 (s_m,(n-1) + s_m,n) : (de_e - dC_m) dV. With
!> s = 2 G_inf e_e + sum_m 2 G_m C_m (which the update keeps exactly), the
!> trapezoid on sigma : de splits exactly into dU, dD_p and dD_v, so
!> W - U - D_p - D_v is the work of the out-of-balance forces Newton leaves.
module visco2d_plastic_quasistatic
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, whole_body_factor, energy_basis
  use visco2d_error, only: error_t, set_error, locate_error
  use visco2d_strings, only: integer_text, message_real, short_real
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: material_t, elastic_matrix, stress_from_strain
  use visco2d_model, only: settings_t, loads_t, probe_t, time_stage_t, source_t, stage_total_steps
  use visco2d_progress, only: progress_step
  use visco2d_element, only: element_b_matrices, gauss_count
  use visco2d_banded, only: band_matrix_t, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card, solve_failure_text, correction_energy
  use visco2d_assembly, only: element_dofs, assemble_point_tangents, external_load, gravity_load, support_mask, &
                              prescribed_displacement, &
                              scatter_add, nodal_field
  use visco2d_solve_errors, only: singular_error, not_finite_error
  use visco2d_plasticity, only: return_result_t, consistent_tangent, viscoplastic_update
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients, viscoelastic_state_t, &
                                  viscoelastic_state_create, element_terms, history_stress, update_history, &
                                  deviatoric_part, deviatoric_stress, stored_energy_density
  use visco2d_quasistatic, only: quasistatic_history_define, quasistatic_row, quasistatic_snapshot, zero_padded
  use visco2d_field_summary, only: put_field_summary, put_probe_summary
  use visco2d_record, only: record_t, record_put, record_put_integer, record_put_real
  use visco2d_plastic_static, only: plastic_summary_t, plastic_record, force_tolerance, energy_tolerance
  implicit none
  private

  public :: solve_plastic_quasistatic

  !> The energy books of a plastic quasi-static run (module comment), per radian in axisymmetry, J.
  type :: quasistatic_energies_t
    real(dp) :: external_work = 0.0_dp   !< W, the trapezoidal work of the loads and the reactions
    real(dp) :: stored = 0.0_dp          !< U at the end, the springs' energy
    real(dp) :: viscous = 0.0_dp         !< D_v, the dashpots' dissipation
  end type quasistatic_energies_t

contains

  !> The quasi-static analysis of a deck with a PLASTIC material (module
  !> comment) into `record`: the keys, history rows and snapshots of
  !> solve_quasistatic, the plastic keys of the static plastic run
  !> (plastic_record, without load_increments) and the energy books
  !> (external_work_J, strain_energy_J, viscous_dissipation_J, balance_error_J).
  subroutine solve_plastic_quasistatic(mesh, materials, settings, loads, probes, stages, source, record, error)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    type(probe_t), intent(in) :: probes(:)
    type(time_stage_t), intent(in) :: stages(:)
    type(source_t), intent(in) :: source
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: b(:, :, :, :), weight(:, :), tangent(:, :, :, :)
    real(dp), allocatable :: stress(:, :, :), strain(:, :, :), ebar(:, :), plastic_strain(:, :, :)   ! committed
    real(dp), allocatable :: trial_stress(:, :, :), trial_strain(:, :, :), trial_ebar(:, :), plastic(:, :, :)
    real(dp), allocatable :: step_backward(:, :)
    real(dp), allocatable :: load(:), load_start(:), gravity(:), target(:), u(:), u_start(:), du(:), rhs(:)
    real(dp), allocatable :: force(:), force_start(:), r(:)
    type(step_coefficients_t), allocatable :: coefficients(:)   !< per material, for the current dt
    type(viscoelastic_state_t) :: history, trial_history
    logical, allocatable :: fixed(:)
    type(band_matrix_t) :: stiffness
    type(factor_t) :: factor
    type(plastic_summary_t) :: summary
    type(quasistatic_energies_t) :: books
    real(dp) :: t, dt, stage_start, equilibrium_error
    real(dp) :: force_level, energy_level     !< the largest |R|, |F| and |u . F| of the steps so far
    integer :: nelem, e, k, step, stage, first_step, factorizations, max_iterations

    nelem = mesh%nelem
    max_iterations = settings%iterations
    allocate(coefficients(size(materials)))
    allocate(b(4, 8, gauss_count, nelem), weight(gauss_count, nelem), tangent(4, 4, gauss_count, nelem))
    do e = 1, nelem
      call element_b_matrices(settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), b(:, :, :, e), weight(:, e), &
                              settings%formulation)
    end do
    allocate(stress(4, gauss_count, nelem), strain(4, gauss_count, nelem), ebar(gauss_count, nelem), &
             plastic_strain(4, gauss_count, nelem), plastic(4, gauss_count, nelem), step_backward(gauss_count, nelem))
    stress = 0.0_dp
    strain = 0.0_dp
    ebar = 0.0_dp
    plastic_strain = 0.0_dp
    trial_stress = stress
    trial_strain = strain
    trial_ebar = ebar
    call viscoelastic_state_create(materials, mesh%element_material, history)   ! none for elastic elements
    trial_history = history
    fixed = support_mask(mesh, settings, loads)
    gravity = gravity_load(mesh, settings, materials, loads)
    allocate(u(2*mesh%nnode), force(2*mesh%nnode), load_start(2*mesh%nnode))
    u = 0.0_dp
    force = 0.0_dp
    load_start = 0.0_dp
    factorizations = 0
    equilibrium_error = 0.0_dp
    force_level = 0.0_dp
    energy_level = 0.0_dp
    summary%increments = stage_total_steps(stages) + 1

    call quasistatic_history_define(probes, stages, record)
    stage_start = 0.0_dp
    do stage = 0, size(stages)                         ! step 0 (t = 0, dt = 0), then each TIME stage
      if (stage == 0) then
        first_step = 0
        dt = 0.0_dp
      else
        first_step = 1
        dt = stages(stage)%dt
      end if
      do step = first_step, merge(0, stages(max(stage, 1))%steps, stage == 0)
        t = stage_start + step*dt
        if (stage > 0) then                            ! (no stages(0): Fortran's .and. does not short-circuit)
          if (step == stages(stage)%steps) t = stages(stage)%end_time
        end if
        if (coefficients(1)%dt /= dt) then
          do k = 1, size(materials)
            coefficients(k) = step_coefficients(materials(k), dt)
          end do
        end if
        call time_step()
        if (allocated(error)) then                     ! at the deck's TIME stage and step
          call locate_error(error, source%file, stages(max(stage, 1))%line, 'TIME', ' at step '// &
                            integer_text(sum(stages(:stage - 1)%steps) + step)//' (t = '//message_real(t)//' s)')
          return
        end if
        call quasistatic_row(mesh, settings, probes, record, t, u, stress, fixed, force - load)
        if (stage > 0) call progress_step(sum(stages(:stage - 1)%steps) + step, t, -1.0_dp)
      end do
      if (stage > 0) stage_start = stages(stage)%end_time
      if (stage == 0) call quasistatic_snapshot(mesh, record, 'step_000000', 'initial', 0.0_dp, u, stress)
    end do
    call quasistatic_snapshot(mesh, record, 'step_'//zero_padded(stage_total_steps(stages)), 'final', t, u, stress)

    books%stored = 0.0_dp
    do e = 1, nelem
      associate (m => materials(mesh%element_material(e)))
      do k = 1, gauss_count
        books%stored = books%stored + weight(k, e)*stored_energy_density(m, strain(:, k, e) - plastic_strain(:, k, e), &
                                                                           point_history(history, e, k))
      end do
      end associate
    end do
    summary%equivalent_plastic = ebar
    summary%equivalent_plastic_max = maxval(ebar)
    summary%yielded_volume = sum(weight, mask=ebar > 0.0_dp)
    if (.not. (ieee_is_finite(books%stored) .and. ieee_is_finite(books%external_work) .and. &
               ieee_is_finite(books%viscous) .and. ieee_is_finite(summary%dissipation))) then
      call not_finite_error(source, 'the plastic quasi-static energies', error)
      return
    end if
    call record_put_integer(record, 'factorizations', factorizations)
    call record_put_integer(record, 'history_values', size(history%history))
    call record_put_real(record, 'time_end_s', t)
    call record_put_real(record, 'equilibrium_error_max', equilibrium_error)
    call record_put(record, 'energy_basis', energy_basis(settings%geometry))
    call put_field_summary(nodal_field(mesh, u), stress, record)
    call put_probe_summary(mesh, probes, nodal_field(mesh, u), stress, record)
    call plastic_record(settings, summary, record, increments=.false.)
    associate (factor => whole_body_factor(settings%geometry))
    call record_put_real(record, 'external_work_J', factor*books%external_work)
    call record_put_real(record, 'strain_energy_J', factor*books%stored)
    call record_put_real(record, 'viscous_dissipation_J', factor*books%viscous)
    call record_put_real(record, 'balance_error_J', factor*(books%external_work - books%stored - summary%dissipation - &
                                                           books%viscous))
    end associate

  contains

    !> One time step to t: Newton to equilibrium (module comment), then the
    !> commit of the stresses, histories and the energy books.
    subroutine time_step()
      real(dp) :: energy_first, energy_next, energy_scale, force_ratio, scale
      integer :: iteration, info
      logical :: converged, first
      load = external_load(mesh, settings, loads, t) + gravity
      target = prescribed_displacement(mesh, loads, t)
      u_start = u
      force_start = force
      call evaluate(0.0_dp*u)                          ! the relaxed start sigma_n + s0 and its tangents
      energy_first = 0.0_dp
      energy_next = 0.0_dp
      energy_scale = 0.0_dp
      force_ratio = 0.0_dp
      converged = .false.
      first = .true.
      do iteration = 1, max_iterations
        call assemble_point_tangents(mesh, b, weight, tangent, stiffness)   ! K_t of the last evaluation
        rhs = load - force
        if (first) then
          call band_constrain_rhs(stiffness, fixed, target - u, rhs)
        else
          call band_constrain_rhs(stiffness, fixed, 0.0_dp*u, rhs)
        end if
        call factor_compute(factor, stiffness, fixed, info, solver_of_card(settings%solver))
        factorizations = factorizations + 1
        if (info > 0) then
          if (factorizations == 1) then
            call singular_error(mesh, source, info, error)
          else
            call set_error(error, 'the tangent stiffness is singular (Newton iteration '//integer_text(iteration)// &
              ', equation '//integer_text(info)//'): the load is probably above the limit load of the perfectly '// &
              'plastic body (give a hardening TANGENT= or SLOPE=, or less load)')
          end if
          return
        end if
        du = rhs
        call factor_solve(factor, du, info)
        if (info /= 0) then
          call set_error(error, solve_failure_text(info))
          return
        end if
        if (first) energy_first = abs(sum(merge(0.0_dp, du*rhs, fixed)))
        first = .false.
        u = u + du
        call evaluate(u - u_start)
        r = load - force
        scale = max(norm2(load), norm2(force), force_level, tiny(1.0_dp))
        force_ratio = norm2(merge(0.0_dp, r, fixed))/scale
        if (.not. (ieee_is_finite(force_ratio) .and. all(ieee_is_finite(u)))) then
          call set_error(error, 'the plastic quasi-static solve diverged (Newton iteration '//integer_text(iteration)// &
            ': the displacement or the residual is not finite)')
          return
        end if
        call correction_energy(factor, r, fixed, energy_next, info)   ! the next correction's, with this factor
        if (info /= 0) then
          call set_error(error, solve_failure_text(info))
          return
        end if
        energy_scale = max(energy_first, abs(dot_product(u, force)), energy_level)   ! a step may barely move
        if (force_ratio <= force_tolerance .and. (energy_next <= energy_tolerance*energy_scale .or. &
                                                  energy_scale == 0.0_dp)) then
          converged = .true.
          exit
        end if
      end do
      if (.not. converged) then
        call set_error(error, 'the plastic quasi-static solve did not converge: after '//integer_text(max_iterations)// &
          ' Newton iterations (ANALYSIS QUASISTATIC ITERATIONS=) the force residual is '//short_real(force_ratio)// &
          ' of the load (tolerance '//short_real(force_tolerance)//') and the energy norm '// &
          short_real(energy_next/max(energy_scale, tiny(1.0_dp)))//' of the first iteration''s or the state''s '// &
          '(tolerance '// &
          short_real(energy_tolerance)//'): give this TIME stage a smaller DT, more ITERATIONS= or a hardening TANGENT=')
        return
      end if
      force_level = max(force_level, norm2(load), norm2(force))
      energy_level = max(energy_level, abs(dot_product(u, force)))
      summary%iterations = summary%iterations + iteration
      summary%iterations_max = max(summary%iterations_max, iteration)
      call commit()
      if (.not. all(ieee_is_finite(stress))) then
        call not_finite_error(source, 'the stress at t = '//message_real(t)//' s', error)
        return
      end if
      ! (no check_balance: its 1e-8 of this step's own forces is round-off of the run's where a step ends
      ! near zero stress; the force criterion above, on the run's forces, is the balance check here)
      equilibrium_error = max(equilibrium_error, maxval(abs(merge(0.0_dp, force - load, fixed)))/ &
                              max(maxval(abs(force)), tiny(1.0_dp)))
    end subroutine time_step

    !> The converged step stands: its trapezoidal work, plastic and viscous
    !> dissipation (module comment), then the state.
    subroutine commit()
      real(dp) :: deviatoric(4), volumetric, elastic(4), start_arm(4), end_arm(4)
      real(dp), allocatable :: start_history(:, :), end_history(:, :)
      integer :: el, gp, term
      books%external_work = books%external_work + 0.5_dp*dot_product( &
        merge(force_start, load_start, fixed) + merge(force, load, fixed), u - u_start)
      do el = 1, nelem
        associate (m => materials(mesh%element_material(el)))
        do gp = 1, gauss_count
          summary%dissipation = summary%dissipation + weight(gp, el)*0.5_dp* &
            dot_product(deviator(stress(:, gp, el)) + deviator(trial_stress(:, gp, el)), plastic(:, gp, el))
          summary%dissipation_backward = summary%dissipation_backward + weight(gp, el)*step_backward(gp, el)
          if (element_terms(history, el) == 0) cycle
          start_history = point_history(history, el, gp)
          end_history = point_history(trial_history, el, gp)
          call deviatoric_part(trial_strain(:, gp, el) - strain(:, gp, el), deviatoric, volumetric)
          elastic = deviatoric - plastic(:, gp, el)
          do term = 1, size(start_history, 2)
            start_arm = deviatoric_stress(m%prony_shear(term), start_history(:, term))
            end_arm = deviatoric_stress(m%prony_shear(term), end_history(:, term))
            books%viscous = books%viscous + weight(gp, el)*0.5_dp* &
              dot_product(start_arm + end_arm, elastic - (end_history(:, term) - start_history(:, term)))
          end do
        end do
        end associate
      end do
      stress = trial_stress
      strain = trial_strain
      ebar = trial_ebar
      plastic_strain = plastic_strain + plastic
      history%history = trial_history%history
      load_start = load
    end subroutine commit

    !> Stresses, histories, tangents and the internal force at
    !> u = u_start + increment: every Gauss point updated from the step's
    !> start over the step of `coefficients` (module comment).
    subroutine evaluate(increment)
      real(dp), intent(in) :: increment(:)
      type(return_result_t) :: state
      real(dp) :: local(8), de(4), f(8), s0(4), deviatoric(4), volumetric
      real(dp), allocatable :: point(:, :)
      integer :: el, gp, nterm, slot
      force = 0.0_dp
      do el = 1, nelem
        local = increment(element_dofs(mesh, el))
        nterm = element_terms(history, el)
        associate (m => materials(mesh%element_material(el)), c => coefficients(mesh%element_material(el)))
        f = 0.0_dp
        do gp = 1, gauss_count
          de = matmul(b(:, :, gp, el), local)
          trial_strain(:, gp, el) = strain(:, gp, el) + de
          point = point_history(history, el, gp)
          if (.not. m%plastic) then                    ! the legacy update, eqs. [13], [14], [23], [24]
            s0 = 0.0_dp
            if (nterm > 0) s0 = history_stress(m, c, point)
            trial_stress(:, gp, el) = stress(:, gp, el) + s0 + stress_from_strain(c%shear, c%bulk, de)
            if (nterm > 0) then
              call deviatoric_part(de, deviatoric, volumetric)
              call update_history(c, deviatoric, point)
            end if
            trial_ebar(gp, el) = ebar(gp, el)
            plastic(:, gp, el) = 0.0_dp
            step_backward(gp, el) = 0.0_dp
            tangent(:, :, gp, el) = elastic_matrix(c%shear, c%bulk)
          else                                         ! the slider in series, eq. [24] with de - de_p
            trial_stress(:, gp, el) = stress(:, gp, el)
            trial_ebar(gp, el) = ebar(gp, el)
            call viscoplastic_update(m, c, m%hardening, de, trial_stress(:, gp, el), point, trial_ebar(gp, el), state)
            plastic(:, gp, el) = state%plastic_increment
            step_backward(gp, el) = state%dissipation
            tangent(:, :, gp, el) = consistent_tangent(c%bulk, c%shear, state)
          end if
          if (nterm > 0) then
            slot = history%first(el) + (gp - 1)*nterm
            trial_history%history(:, slot:slot + nterm - 1) = point
          end if
          f = f + weight(gp, el)*matmul(transpose(b(:, :, gp, el)), trial_stress(:, gp, el))
        end do
        end associate
        call scatter_add(mesh, el, f, force)
      end do
    end subroutine evaluate
  end subroutine solve_plastic_quasistatic

  !> The histories (4, nterm) of Gauss point gp of element e (none for an element without memory).
  pure function point_history(state, e, gp) result(point)
    type(viscoelastic_state_t), intent(in) :: state
    integer, intent(in) :: e, gp
    real(dp), allocatable :: point(:, :)
    integer :: nterm, slot
    nterm = element_terms(state, e)
    slot = state%first(e) + (gp - 1)*nterm
    point = state%history(:, slot:slot + nterm - 1)
  end function point_history

  !> The deviatoric part (s_r, s_z, s_theta, s_rz) of a stress.
  pure function deviator(sigma) result(s)
    real(dp), intent(in) :: sigma(4)
    real(dp) :: s(4)
    s = sigma
    s(1:3) = s(1:3) - sum(sigma(1:3))/3.0_dp
  end function deviator
end module visco2d_plastic_quasistatic
