!> The legacy program's quasi-static time loop for viscoelastic bodies
!> (ANALYSIS QUASISTATIC): step 0 is the instantaneous response at t = 0
!> (dt = 0, so mu = G(0)); each later step n solves
!>   S_n dU = R(t_n) - F(sigma_{n-1} + s0_n)
!> with S_n assembled from mu_n (eq. [21]) and the history stress s0_n
!> (eq. [23]) as a pseudo-load, then updates stress and history
!> (eqs. [13], [14], [24]; the history stress and update shared with the
!> dynamic loop, module visco2d_constitutive). Writing the right-hand
!> side as the full out-of-balance force (not Delta R alone) keeps round-off
!> from accumulating into drift. S_n depends on dt only, so its factor is
!> reused while dt is constant (elastic bodies: one factorization in all).
module visco2d_quasistatic
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, whole_body_factor, energy_basis
  use visco2d_error, only: error_t, set_error, locate_error
  use visco2d_strings, only: integer_text, message_real
  use visco2d_mesh, only: mesh_t
  use visco2d_model, only: settings_t, loads_t, probe_t, time_stage_t, source_t, stage_total_steps
  use visco2d_progress, only: progress_step
  use visco2d_material, only: material_t, stress_from_strain, has_memory
  use visco2d_element, only: element_strains, element_internal_force
  use visco2d_banded, only: band_matrix_t, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card, solve_failure_text
  use visco2d_assembly, only: assemble_stiffness, external_load, support_mask, node_dof, gather, &
                              prescribed_displacement, internal_force, scatter_add, gravity_load, &
                              nodal_field
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients, viscoelastic_state_t, &
                                  viscoelastic_state_create, element_terms
  use visco2d_constitutive, only: history_stresses, commit_history
  use visco2d_record, only: record_t, snapshot_t, record_put, record_put_real, record_put_integer, &
                            history_define, history_append, record_add_snapshot
  use visco2d_solve_errors, only: check_balance, singular_error, not_finite_error
  use visco2d_field_summary, only: set_snapshot_stress, put_field_summary, put_probe_summary
  use visco2d_stress_recovery, only: node_stress
  implicit none
  private

  public :: solve_quasistatic
  public :: quasistatic_history_define, quasistatic_row, quasistatic_snapshot, zero_padded   ! for the plastic loop

  !> The state of a quasi-static run between increments: the stiffness S_n
  !> and its factor for the current step length, the step constants, the
  !> displacement, stresses and Prony histories, and the work arrays.
  type :: quasistatic_t
    type(band_matrix_t) :: stiffness
    type(factor_t) :: factor
    type(step_coefficients_t), allocatable :: coefficients(:)   !< per material, for the current dt
    type(viscoelastic_state_t) :: history                        !< the Prony histories (with memory)
    logical :: memory = .false.                                  !< a material of the mesh has memory
    logical, allocatable :: fixed(:)                             !< supported equations
    real(dp), allocatable :: u(:), du(:), rhs(:), load(:), internal(:), gravity(:)
    real(dp), allocatable :: stress(:, :, :), trial(:, :, :), s0(:, :, :), increments(:, :, :)
    real(dp), allocatable :: shear(:), bulk(:)                    !< per element, mu_n and K
    integer :: factorizations = 0
    real(dp) :: equilibrium_error = 0.0_dp                       !< largest |F - R| / |F| off the supports
  end type quasistatic_t

contains

  !> The quasi-static incremental analysis (ANALYSIS QUASISTATIC) of a mesh
  !> of these materials under these supports and loads, over the time
  !> stages; `source` locates a failure in the input file. Fills the record
  !> with the summary, one history row per step (step 0 at t = 0 included)
  !> and snapshots at t = 0 and at the end.
  subroutine solve_quasistatic(mesh, materials, settings, loads, probes, stages, source, record, error)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    type(probe_t), intent(in) :: probes(:)
    type(time_stage_t), intent(in) :: stages(:)
    type(source_t), intent(in) :: source
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    type(quasistatic_t) :: solution
    integer :: step, stage, first_step
    real(dp) :: t, dt, stage_start

    call quasistatic_start(mesh, materials, settings, loads, solution)
    call quasistatic_history_define(probes, stages, record)
    ! Step 0 (t = 0, dt = 0), then each TIME stage.
    stage_start = 0.0_dp
    do stage = 0, size(stages)
      if (stage == 0) then
        first_step = 0
        dt = 0.0_dp
      else
        first_step = 1
        dt = stages(stage)%dt
      end if
      do step = first_step, merge(0, stages(max(stage, 1))%steps, stage == 0)
        t = stage_start + step*dt
        if (stage > 0) then                                ! (no stages(0): Fortran's .and. does not short-circuit)
          if (step == stages(stage)%steps) t = stages(stage)%end_time
        end if
        if (solution%coefficients(1)%dt /= dt .and. (solution%memory .or. solution%factorizations == 0)) then
          call quasistatic_factor(mesh, materials, settings, source, solution, dt, error)
          if (allocated(error)) return
        end if
        call quasistatic_increment(mesh, materials, settings, loads, source, solution, t, error)
        if (allocated(error)) then                     ! a failed solve: at the deck's TIME stage and step
          call locate_error(error, source%file, stages(max(stage, 1))%line, 'TIME', ' at step '// &
                            integer_text(sum(stages(:stage - 1)%steps) + step)//' (t = '//message_real(t)//' s)')
          return
        end if
        call quasistatic_row(mesh, settings, probes, record, t, solution%u, solution%stress, solution%fixed, &
                             solution%internal - solution%load)
        if (stage > 0) call progress_step(sum(stages(:stage - 1)%steps) + step, t, -1.0_dp)
      end do
      if (stage > 0) stage_start = stages(stage)%end_time
      if (stage == 0) call quasistatic_snapshot(mesh, record, 'step_000000', 'initial', 0.0_dp, solution%u, &
                                                solution%stress)
    end do
    call quasistatic_snapshot(mesh, record, 'step_'//zero_padded(stage_total_steps(stages)), 'final', t, solution%u, &
                              solution%stress)
    call record_put_integer(record, 'factorizations', solution%factorizations)
    if (solution%memory) then
      call record_put_integer(record, 'history_values', size(solution%history%history))
    else
      call record_put_integer(record, 'history_values', 0)     ! an elastic body allocates no history
    end if
    call record_put_real(record, 'time_end_s', t)
    call record_put_real(record, 'equilibrium_error_max', solution%equilibrium_error)
    call record_put(record, 'energy_basis', energy_basis(settings%geometry))   ! of the reaction columns
    call put_field_summary(nodal_field(mesh, solution%u), solution%stress, record)
    call put_probe_summary(mesh, probes, nodal_field(mesh, solution%u), solution%stress, record)
  end subroutine solve_quasistatic

  !> The state at t = 0: no displacement or stress, the Prony histories at 0
  !> (a body with memory), the supports and gravity, nothing factored.
  subroutine quasistatic_start(mesh, materials, settings, loads, solution)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    type(quasistatic_t), intent(out) :: solution
    integer :: k
    solution%memory = .false.
    do k = 1, size(materials)
      if (has_memory(materials(k)) .and. any(mesh%element_material == k)) solution%memory = .true.
    end do
    if (solution%memory) call viscoelastic_state_create(materials, mesh%element_material, solution%history)
    allocate(solution%coefficients(size(materials)))
    solution%fixed = support_mask(mesh, settings, loads)
    solution%gravity = gravity_load(mesh, settings, materials, loads)
    allocate(solution%u(2*mesh%nnode), solution%du(2*mesh%nnode), solution%internal(2*mesh%nnode))
    solution%u = 0.0_dp
    solution%internal = 0.0_dp
    allocate(solution%stress(4, 4, mesh%nelem), solution%trial(4, 4, mesh%nelem), solution%shear(mesh%nelem), &
             solution%bulk(mesh%nelem), solution%s0(4, 4, mesh%nelem), solution%increments(4, 4, mesh%nelem))
    solution%stress = 0.0_dp
  end subroutine quasistatic_start

  !> S_n with the moduli (mu_n, K) of step length dt (eq. [21]), constrained
  !> and factored; an error at an element's card if it is singular.
  subroutine quasistatic_factor(mesh, materials, settings, source, solution, dt, error)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(source_t), intent(in) :: source
    type(quasistatic_t), intent(inout) :: solution
    real(dp), intent(in) :: dt
    type(error_t), allocatable, intent(inout) :: error
    integer :: info, m
    do m = 1, size(materials)
      solution%coefficients(m) = step_coefficients(materials(m), dt)
    end do
    solution%shear = solution%coefficients(mesh%element_material)%shear
    solution%bulk = solution%coefficients(mesh%element_material)%bulk
    call assemble_stiffness(mesh, settings, solution%shear, solution%bulk, solution%stiffness)
    call factor_compute(solution%factor, solution%stiffness, solution%fixed, info, solver_of_card(settings%solver))
    solution%factorizations = solution%factorizations + 1
    if (info > 0) call singular_error(mesh, source, info, error)
  end subroutine quasistatic_factor

  !> One increment to time t: the pseudo-load of the history stress
  !> (eq. [23]), the solve S_n dU = R(t_n) - F(sigma_{n-1} + s0_n), the
  !> stress update (eqs. [13], [14]) and the histories (eq. [24]); an error
  !> if a value is not finite or the solution is out of balance.
  subroutine quasistatic_increment(mesh, materials, settings, loads, source, solution, t, error)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    type(source_t), intent(in) :: source
    type(quasistatic_t), intent(inout) :: solution
    real(dp), intent(in) :: t
    type(error_t), allocatable, intent(inout) :: error
    integer :: e, g, status
    associate (q => solution)
    q%trial = q%stress
    q%rhs = -q%internal                                ! F(sigma_{n-1})
    if (q%memory) then
      call history_stresses(materials, mesh%element_material, q%history, q%coefficients, q%s0)   ! eq. [23]
      do e = 1, mesh%nelem
        if (element_terms(q%history, e) == 0) cycle
        q%trial(:, :, e) = q%trial(:, :, e) + q%s0(:, :, e)
        call scatter_add(mesh, e, -element_internal_force(settings%geometry, &
          mesh%xy(:, mesh%connectivity(:, e)), q%trial(:, :, e) - q%stress(:, :, e), settings%formulation), q%rhs)
      end do
    end if
    q%load = external_load(mesh, settings, loads, t) + q%gravity
    q%rhs = q%rhs + q%load
    q%du = prescribed_displacement(mesh, loads, t) - q%u      ! increments of the prescribed values
    call band_constrain_rhs(q%stiffness, q%fixed, q%du, q%rhs)
    call factor_solve(q%factor, q%rhs, status)
    if (status /= 0) then
      call set_error(error, solve_failure_text(status))   ! located by solve_quasistatic
      return
    end if
    q%du = q%rhs
    q%u = q%u + q%du
    do e = 1, mesh%nelem
      q%increments(:, :, e) = element_strains(settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), &
                                              gather(mesh, e, q%du), settings%formulation)
      do g = 1, 4                                      ! eqs. [13], [14]
        q%stress(:, g, e) = q%trial(:, g, e) + stress_from_strain(q%shear(e), q%bulk(e), q%increments(:, g, e))
      end do
    end do
    if (q%memory) call commit_history(mesh%element_material, q%history, q%coefficients, q%increments)   ! eq. [24]
    q%internal = internal_force(mesh, settings, q%stress)
    if (.not. all(ieee_is_finite(q%u)) .or. .not. all(ieee_is_finite(q%stress))) then
      call not_finite_error(source, 'the displacement or stress at t = '//message_real(t)//' s', error)
      return
    end if
    q%equilibrium_error = max(q%equilibrium_error, maxval(abs(merge(0.0_dp, q%internal - q%load, q%fixed)))/ &
                              max(maxval(abs(q%internal)), tiny(1.0_dp)))
    call check_balance(mesh, source, q%internal - q%load, q%fixed, q%load, error)
    end associate
  end subroutine quasistatic_increment

  !> The history columns of a quasi-static run: step, time, largest
  !> displacement, support reactions, and per probe its u and nodal stresses.
  subroutine quasistatic_history_define(probes, stages, record)
    type(probe_t), intent(in) :: probes(:)
    type(time_stage_t), intent(in) :: stages(:)
    type(record_t), intent(inout) :: record
    character(len=48), allocatable :: columns(:)
    integer :: p
    columns = [character(len=48) :: 'step', 't_s', 'max_displacement_m', 'reaction_r_N', 'reaction_z_N']
    do p = 1, size(probes)
      columns = [character(len=48) :: columns, probes(p)%name//'_ur_m', probes(p)%name//'_uz_m', &
                 probes(p)%name//'_sr_Pa', probes(p)%name//'_sz_Pa', &
                 probes(p)%name//'_st_Pa', probes(p)%name//'_trz_Pa']
    end do
    call history_define(record, columns, stage_total_steps(stages) + 1)
  end subroutine quasistatic_history_define

  !> One history row of a quasi-static run at time t (`residual` = F - R:
  !> the support reactions on the fixed equations).
  subroutine quasistatic_row(mesh, settings, probes, record, t, u, stress, fixed, residual)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    type(probe_t), intent(in) :: probes(:)
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: t, u(:), stress(:, :, :), residual(:)
    logical, intent(in) :: fixed(:)
    real(dp), allocatable :: row(:)
    integer :: p, node
    row = [real(record%nrow, dp), t, maxval(norm2(reshape(u, [2, mesh%nnode]), dim=1)), &
           whole_body_factor(settings%geometry)*[sum(residual(1::2), mask=fixed(1::2)), &
                                             sum(residual(2::2), mask=fixed(2::2))]]
    do p = 1, size(probes)
      node = probes(p)%node
      row = [row, u(node_dof(mesh, node, 1):node_dof(mesh, node, 2)), node_stress(mesh, stress, node)]
    end do
    call history_append(record, row)
  end subroutine quasistatic_row

  !> A snapshot of a quasi-static run: displacements and stresses.
  subroutine quasistatic_snapshot(mesh, record, name, label, time, u, stress)
    type(mesh_t), intent(in) :: mesh
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: name, label
    real(dp), intent(in) :: time, u(:), stress(:, :, :)
    type(snapshot_t) :: snapshot
    snapshot%name = name
    snapshot%label = label
    snapshot%time = time
    snapshot%displacement = nodal_field(mesh, u)
    call set_snapshot_stress(mesh, stress, snapshot)
    call record_add_snapshot(record, snapshot)
  end subroutine quasistatic_snapshot

  !> n as a six-digit, zero-padded text (snapshot names sort in time order).
  pure function zero_padded(n) result(text)
    integer, intent(in) :: n
    character(len=6) :: text
    write(text, '(i6.6)') n
  end function zero_padded
end module visco2d_quasistatic
