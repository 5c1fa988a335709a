!> The legacy base: static linear analysis S U = R (eq. [25] without inertia),
!> and the legacy program's quasi-static time loop for viscoelastic bodies.
!>
!> STATIC: assemble, impose supports, factor once (visco2d_factor), back-substitute
!> once, recover strains and stresses at the Gauss points and the nodes.
!>
!> QUASISTATIC: step 0 is the instantaneous response at t = 0 (dt = 0, so
!> mu = G(0)); each later step n solves S_n dU = R(t_n) - F(sigma_{n-1} + s0_n)
!> with S_n assembled from mu_n (eq. [21]) and the history stress s0_n
!> (eq. [23]) as a pseudo-load, then updates stress and history
!> (eqs. [13], [14], [24]; the history stress and update shared with the
!> dynamic loop, module visco2d_constitutive). Writing the right-hand
!> side as the full out-of-balance force (not Delta R alone) keeps round-off
!> from accumulating into drift. S_n depends on dt only, so its factor is
!> reused while dt is constant (elastic bodies: one factorization in all).
module visco2d_static
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, whole_body_factor, energy_basis
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: itoa, rtoa
  use visco2d_deck, only: deck_t, total_steps
  use visco2d_progress, only: progress_step
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: stress_from_strain, von_mises, max_shear, has_memory
  use visco2d_element, only: element_strains, gauss_to_node_extrapolation
  use visco2d_banded, only: band_matrix_t, band_multiply, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card
  use visco2d_assembly, only: assemble_stiffness, external_load, support_mask, node_dof, gather, nodal_average, &
                              prescribed_displacement, internal_force, scatter_add, gravity_load, nodal_field
  use visco2d_element, only: element_internal_force
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients, viscoelastic_state_t, &
                                  viscoelastic_state_create, element_terms
  use visco2d_constitutive, only: history_stresses, commit_history
  use visco2d_pad_mesh, only: body_nodes, body_elements
  use visco2d_record, only: record_t, snapshot_t, record_put, record_put_real, record_put_integer, history_define, &
                            history_append, record_add_snapshot
  implicit none
  private

  public :: static_solution_t, solve_static, static_record, singular_message, solve_quasistatic
  public :: singular_error, node_text, card_at_line, not_finite_error
  public :: node_stress, node_corners, corner_stress, put_field_summary, put_probe_summary, set_snapshot_stress

  !> Fields of a static solution.
  type :: static_solution_t
    real(dp), allocatable :: displacement(:, :)   !< (2, nnode) m
    real(dp), allocatable :: reaction(:, :)       !< (2, nnode) N (per radian in axisymmetry)
    real(dp), allocatable :: strain(:, :, :)      !< (4, 4, nelem) at Gauss points
    real(dp), allocatable :: stress(:, :, :)      !< (4, 4, nelem) Pa at Gauss points
    real(dp), allocatable :: nodal_stress(:, :)   !< (4, nnode) Pa
    real(dp) :: strain_energy = 0.0_dp            !< (1/2) u^T S u, J
    real(dp) :: external_work = 0.0_dp            !< (1/2) R^T u, J
  end type static_solution_t

contains

  !> Solve the static problem of a deck. `extra_fixed` / `extra_values`
  !> prescribe further displacements (the contact extension's plate nodes);
  !> `given` is a displacement solved by the caller, of which only the
  !> reactions, energies, strains and stresses are computed.
  subroutine solve_static(deck, solution, error, extra_fixed, extra_values, given)
    type(deck_t), intent(in) :: deck
    type(static_solution_t), intent(out) :: solution
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: extra_fixed(:)
    real(dp), intent(in), optional :: extra_values(:)
    real(dp), intent(in), optional :: given(:)   !< the displacement (band order), solved elsewhere: fields only
    type(band_matrix_t) :: stiffness
    type(factor_t) :: factor
    real(dp), allocatable :: shear(:), bulk(:), load(:), u(:), zero(:)
    logical, allocatable :: fixed(:)
    integer :: e, info

    associate (mesh => deck%mesh)
    shear = deck%materials(mesh%element_material)%shear
    bulk = deck%materials(mesh%element_material)%bulk
    call assemble_stiffness(deck, shear, bulk, stiffness)
    load = external_load(deck, 0.0_dp) + gravity_load(deck)
    fixed = support_mask(deck)
    zero = prescribed_displacement(deck, 0.0_dp)
    if (present(extra_fixed) .and. present(extra_values)) then
      zero = merge(extra_values, zero, extra_fixed)
      fixed = fixed .or. extra_fixed
    end if
    if (present(given)) then                       ! a constrained solve done by the caller (a PAD's contact)
      u = given
    else
      u = load
      call band_constrain_rhs(stiffness, fixed, zero, u)
      call factor_compute(factor, stiffness, fixed, info, solver_of_card(deck%solver))
      if (info > 0) then
        call singular_error(deck, info, error)
        return
      end if
      call factor_solve(factor, u)
    end if
    if (.not. all(ieee_is_finite(u))) then
      call not_finite_error(deck, 'the static displacement', error)
      return
    end if
    if (.not. present(given)) then
      call check_balance(deck, band_multiply(stiffness, u) - load, fixed, load, error)
      if (allocated(error)) return
    end if

    solution%displacement = nodal_field(mesh, u)
    associate (residual => band_multiply(stiffness, u) - load)
    solution%reaction = nodal_field(mesh, residual)
    solution%strain_energy = 0.5_dp*dot_product(u, residual + load)
    end associate
    solution%external_work = 0.5_dp*dot_product(load, u)

    allocate(solution%strain(4, 4, mesh%nelem), solution%stress(4, 4, mesh%nelem))
    do e = 1, mesh%nelem
      solution%strain(:, :, e) = element_strains(deck%geometry, mesh%xy(:, mesh%connectivity(:, e)), &
                                                 gather(mesh, e, u), deck%formulation)
      do info = 1, 4
        solution%stress(:, info, e) = stress_from_strain(shear(e), bulk(e), solution%strain(:, info, e))
      end do
    end do
    solution%nodal_stress = nodal_average(mesh, solution%stress)
    if (.not. all(ieee_is_finite(solution%stress)) .or. .not. all(ieee_is_finite(solution%reaction)) .or. &
        .not. ieee_is_finite(solution%strain_energy) .or. .not. ieee_is_finite(solution%external_work)) &
      call not_finite_error(deck, 'the static stress, reaction or energy', error)
    end associate
  end subroutine solve_static

  !> A solve of a singular stiffness can pass the factor's pivot test (a body
  !> with no support along z: its rigid translation) and return a huge,
  !> meaningless displacement. Then the free equations are out of balance:
  !> the residual K u - R there, round-off for a true solution, is above
  !> 1e-8 of the loads and the support reactions. That is the singular-
  !> stiffness error, at the worst equation.
  subroutine check_balance(deck, residual, fixed, load, error)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: residual(:), load(:)
    logical, intent(in) :: fixed(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: scale
    integer :: worst
    scale = max(maxval(abs(load)), maxval(abs(merge(residual, 0.0_dp, fixed))), tiny(1.0_dp))
    worst = maxloc(abs(merge(0.0_dp, residual, fixed)), dim=1)
    if (abs(residual(worst)) > 1.0e-8_dp*scale .and. .not. fixed(worst)) call singular_error(deck, worst, error)
  end subroutine check_balance

  !> Message for a factorization failure at band equation `equation`.
  function singular_message(deck, equation) result(message)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    character(:), allocatable :: message
    message = 'the stiffness matrix is singular or not positive definite'//node_text(deck, equation)// &
      ': the body can probably move freely (a rigid-body mode); add FIX cards'// &
      ' that stop it, or check the material constants'
  end function singular_message

  !> The error of a static factorization failure at band equation `equation`,
  !> located at the card that defined an element holding that node.
  subroutine singular_error(deck, equation, error)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    type(error_t), allocatable, intent(inout) :: error
    integer :: line
    line = equation_line(deck, equation)
    call set_error(error, singular_message(deck, equation), file=deck%cards%file, line=line, &
                   card=card_at_line(deck, line))
  end subroutine singular_error

  !> ' at node N (u_z)' for band equation `equation` ('' if not found).
  function node_text(deck, equation) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    character(:), allocatable :: text
    integer :: node
    text = ''
    node = equation_node(deck, equation)
    if (node > 0) text = ' at node '//itoa(deck%mesh%node_id(node))//' ('// &
                         trim(merge('u_r', 'u_z', mod(equation, 2) == 1))//')'
  end function node_text

  !> The node (index) of band equation `equation` (0 if none).
  pure integer function equation_node(deck, equation) result(node)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    integer :: k
    node = 0
    do k = 1, deck%mesh%nnode
      if (deck%mesh%equation(k) == (equation - 1)/2 + 1) then
        node = k
        return
      end if
    end do
  end function equation_node

  !> The deck line of the first element holding the node of band equation
  !> `equation` (its ELEMENT or MESH card; 0 if not known).
  pure integer function equation_line(deck, equation) result(line)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    integer :: node, e
    line = 0
    node = equation_node(deck, equation)
    if (node == 0 .or. .not. allocated(deck%mesh%element_line)) return
    do e = 1, deck%mesh%nelem
      if (any(deck%mesh%connectivity(:, e) == node)) then
        line = deck%mesh%element_line(e)
        return
      end if
    end do
  end function equation_line

  !> The keyword of the card at deck line `line` ('' if none).
  pure function card_at_line(deck, line) result(keyword)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    character(:), allocatable :: keyword
    integer :: k
    keyword = ''
    if (.not. allocated(deck%cards%cards)) return
    do k = 1, size(deck%cards%cards)
      if (deck%cards%cards(k)%line == line) then
        keyword = deck%cards%cards(k)%keyword
        return
      end if
    end do
  end function card_at_line

  !> The error when a result is not finite (NaN or Inf): located at the
  !> ANALYSIS card, naming what overflowed, so no such value reaches an output.
  subroutine not_finite_error(deck, what, error)
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: what
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, line
    line = 0
    if (allocated(deck%cards%cards)) then
      do k = 1, size(deck%cards%cards)
        if (deck%cards%cards(k)%keyword == 'ANALYSIS') then
          line = deck%cards%cards(k)%line
          exit
        end if
      end do
    end if
    call set_error(error, what//' is not finite (NaN or Inf): the loads, moduli or prescribed values '// &
      'overflow double precision; check their magnitudes. No results were written.', file=deck%cards%file, &
      line=line, card='ANALYSIS')
  end subroutine not_finite_error

  !> Summary, one-row history and the final snapshot of a static solution.
  subroutine static_record(deck, solution, record)
    type(deck_t), intent(in) :: deck
    type(static_solution_t), intent(in) :: solution
    type(record_t), intent(inout) :: record
    type(snapshot_t) :: snapshot
    character(len=48), allocatable :: columns(:)
    real(dp), allocatable :: row(:)
    integer :: k, node, c
    character(len=6), parameter :: probe_columns(6) = ['ur_m  ', 'uz_m  ', 'sr_Pa ', 'sz_Pa ', 'st_Pa ', 'trz_Pa']

    associate (mesh => deck%mesh)
    call put_field_summary(solution%displacement(:, :body_nodes(deck)), solution%stress(:, :, :body_elements(deck)), &
                           record)
    ! Energies and reactions on the energy_basis (whole body in axisymmetry).
    associate (factor => whole_body_factor(deck%geometry))
    call record_put(record, 'energy_basis', energy_basis(deck%geometry))
    call record_put_real(record, 'strain_energy_J', factor*solution%strain_energy)
    call record_put_real(record, 'external_work_J', factor*solution%external_work)
    call record_put_real(record, 'reaction_r_N', factor*sum(solution%reaction(1, :)))
    call record_put_real(record, 'reaction_z_N', factor*sum(solution%reaction(2, :)))

    columns = [character(len=48) :: 'step', 't_s', 'max_displacement_m', 'strain_J', 'work_J']
    row = [1.0_dp, 0.0_dp, maxval(norm2(solution%displacement, dim=1)), factor*solution%strain_energy, &
           factor*solution%external_work]
    end associate
    call put_probe_summary(deck, solution%displacement, solution%stress, record)
    do k = 1, size(deck%probes)
      node = deck%probes(k)%node
      do c = 1, 6
        columns = [character(len=48) :: columns, deck%probes(k)%name//'_'//trim(probe_columns(c))]
      end do
      row = [row, solution%displacement(:, node), solution%nodal_stress(:, node)]
    end do
    call history_define(record, columns, 1)
    call history_append(record, row)

    snapshot%name = 'step_000001'
    snapshot%label = 'static'
    snapshot%time = 0.0_dp
    snapshot%displacement = solution%displacement
    call set_snapshot_stress(mesh, solution%stress, snapshot)
    call record_add_snapshot(record, snapshot)
    end associate
  end subroutine static_record
  !> The quasi-static incremental analysis of a deck (ANALYSIS QUASISTATIC):
  !> fills the record with the summary, one history row per step (step 0 at
  !> t = 0 included) and snapshots at t = 0 and at the end.
  subroutine solve_quasistatic(deck, record, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    type(band_matrix_t) :: stiffness
    type(factor_t) :: factor
    type(step_coefficients_t), allocatable :: coefficients(:)
    type(viscoelastic_state_t) :: state
    real(dp), allocatable :: u(:), du(:), rhs(:), load(:), internal(:), stress(:, :, :), trial(:, :, :)
    real(dp), allocatable :: shear(:), bulk(:), gravity(:)
    logical, allocatable :: fixed(:)
    logical :: memory
    integer :: step, stage, k, e, g, factorizations, first_step
    real(dp) :: t, dt, stage_start, equilibrium_error
    real(dp), allocatable :: s0(:, :, :), increments(:, :, :)

    associate (mesh => deck%mesh, materials => deck%materials)
    memory = .false.
    do k = 1, size(materials)
      if (has_memory(materials(k)) .and. any(mesh%element_material == k)) memory = .true.
    end do
    if (memory) call viscoelastic_state_create(materials, mesh%element_material, state)
    allocate(coefficients(size(materials)))
    fixed = support_mask(deck)
    gravity = gravity_load(deck)
    allocate(u(2*mesh%nnode), du(2*mesh%nnode), internal(2*mesh%nnode))
    u = 0.0_dp
    internal = 0.0_dp
    allocate(stress(4, 4, mesh%nelem), trial(4, 4, mesh%nelem), shear(mesh%nelem), bulk(mesh%nelem), &
             s0(4, 4, mesh%nelem), increments(4, 4, mesh%nelem))
    stress = 0.0_dp
    factorizations = 0
    equilibrium_error = 0.0_dp
    call quasistatic_history_define(deck, record)

    ! Step 0 (t = 0, dt = 0), then each TIME stage.
    stage_start = 0.0_dp
    do stage = 0, size(deck%stages)
      if (stage == 0) then
        first_step = 0
        dt = 0.0_dp
      else
        first_step = 1
        dt = deck%stages(stage)%dt
      end if
      do step = first_step, merge(0, deck%stages(max(stage, 1))%steps, stage == 0)
        t = stage_start + step*dt
        if (stage > 0) then                                ! (no stages(0): Fortran's .and. does not short-circuit)
          if (step == deck%stages(stage)%steps) t = deck%stages(stage)%end_time
        end if
        if (coefficients(1)%dt /= dt .and. (memory .or. factorizations == 0)) then
          call quasistatic_factor(dt)
          if (allocated(error)) return
        end if
        call quasistatic_increment(t)
        if (allocated(error)) return
        if (stage > 0) call progress_step(sum(deck%stages(:stage - 1)%steps) + step, t, -1.0_dp)
      end do
      if (stage > 0) stage_start = deck%stages(stage)%end_time
      if (stage == 0) call quasistatic_snapshot(deck, record, 'step_000000', 'initial', 0.0_dp, u, stress)
    end do
    call quasistatic_snapshot(deck, record, 'step_'//zero_padded(total_steps(deck)), 'final', t, u, stress)
    call record_put_integer(record, 'factorizations', factorizations)
    if (memory) then
      call record_put_integer(record, 'history_values', size(state%history))
    else
      call record_put_integer(record, 'history_values', 0)     ! an elastic body allocates no history
    end if
    call record_put_real(record, 'time_end_s', t)
    call record_put_real(record, 'equilibrium_error_max', equilibrium_error)
    call record_put(record, 'energy_basis', energy_basis(deck%geometry))   ! of the reaction columns
    call put_field_summary(nodal_field(deck%mesh, u), stress, record)
    call put_probe_summary(deck, nodal_field(deck%mesh, u), stress, record)
    end associate

  contains

    !> S_n with the moduli (mu_n, K) of step length dt, constrained and factored.
    subroutine quasistatic_factor(dt)
      real(dp), intent(in) :: dt
      integer :: info, m
      do m = 1, size(deck%materials)
        coefficients(m) = step_coefficients(deck%materials(m), dt)
      end do
      shear = coefficients(deck%mesh%element_material)%shear
      bulk = coefficients(deck%mesh%element_material)%bulk
      call assemble_stiffness(deck, shear, bulk, stiffness)
      call factor_compute(factor, stiffness, fixed, info, solver_of_card(deck%solver))
      factorizations = factorizations + 1
      if (info > 0) call singular_error(deck, info, error)
    end subroutine quasistatic_factor

    !> One increment to time t: pseudo-load, solve, stress and history update.
    subroutine quasistatic_increment(t)
      real(dp), intent(in) :: t
      trial = stress
      rhs = -internal                                   ! F(sigma_{n-1})
      if (memory) then
        call history_stresses(deck%materials, deck%mesh%element_material, state, coefficients, s0)   ! eq. [23]
        do e = 1, deck%mesh%nelem
          if (element_terms(state, e) == 0) cycle
          trial(:, :, e) = trial(:, :, e) + s0(:, :, e)
          call scatter_add(deck%mesh, e, -element_internal_force(deck%geometry, &
            deck%mesh%xy(:, deck%mesh%connectivity(:, e)), trial(:, :, e) - stress(:, :, e), deck%formulation), rhs)
        end do
      end if
      load = external_load(deck, t) + gravity
      rhs = rhs + load
      du = prescribed_displacement(deck, t) - u          ! increments of the prescribed values
      call band_constrain_rhs(stiffness, fixed, du, rhs)
      call factor_solve(factor, rhs)
      du = rhs
      u = u + du
      do e = 1, deck%mesh%nelem
        increments(:, :, e) = element_strains(deck%geometry, deck%mesh%xy(:, deck%mesh%connectivity(:, e)), &
                                              gather(deck%mesh, e, du), deck%formulation)
        do g = 1, 4
          stress(:, g, e) = trial(:, g, e) + stress_from_strain(shear(e), bulk(e), increments(:, g, e))  ! [13], [14]
        end do
      end do
      if (memory) call commit_history(deck%mesh%element_material, state, coefficients, increments)   ! eq. [24]
      internal = internal_force(deck, stress)
      if (.not. all(ieee_is_finite(u)) .or. .not. all(ieee_is_finite(stress))) then
        call not_finite_error(deck, 'the displacement or stress at t = '//rtoa(t)//' s', error)
        return
      end if
      equilibrium_error = max(equilibrium_error, maxval(abs(merge(0.0_dp, internal - load, fixed)))/ &
                              max(maxval(abs(internal)), tiny(1.0_dp)))
      call check_balance(deck, internal - load, fixed, load, error)
      if (allocated(error)) return
      call quasistatic_row(deck, record, t, u, stress, fixed, internal - load)
    end subroutine quasistatic_increment
  end subroutine solve_quasistatic

  !> The history columns of a quasi-static run: step, time, largest
  !> displacement, support reactions, and per probe its u and nodal stresses.
  subroutine quasistatic_history_define(deck, record)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    character(len=48), allocatable :: columns(:)
    integer :: p
    columns = [character(len=48) :: 'step', 't_s', 'max_displacement_m', 'reaction_r_N', 'reaction_z_N']
    do p = 1, size(deck%probes)
      columns = [character(len=48) :: columns, deck%probes(p)%name//'_ur_m', deck%probes(p)%name//'_uz_m', &
                 deck%probes(p)%name//'_sr_Pa', deck%probes(p)%name//'_sz_Pa', &
                 deck%probes(p)%name//'_st_Pa', deck%probes(p)%name//'_trz_Pa']
    end do
    call history_define(record, columns, total_steps(deck) + 1)
  end subroutine quasistatic_history_define

  !> One history row of a quasi-static run at time t (`residual` = F - R:
  !> the support reactions on the fixed equations).
  subroutine quasistatic_row(deck, record, t, u, stress, fixed, residual)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: t, u(:), stress(:, :, :), residual(:)
    logical, intent(in) :: fixed(:)
    real(dp), allocatable :: row(:)
    integer :: p, node
    row = [real(record%nrow, dp), t, maxval(norm2(reshape(u, [2, deck%mesh%nnode]), dim=1)), &
           whole_body_factor(deck%geometry)*[sum(residual(1::2), mask=fixed(1::2)), &
                                             sum(residual(2::2), mask=fixed(2::2))]]
    do p = 1, size(deck%probes)
      node = deck%probes(p)%node
      row = [row, u(node_dof(deck%mesh, node, 1):node_dof(deck%mesh, node, 2)), node_stress(deck%mesh, stress, node)]
    end do
    call history_append(record, row)
  end subroutine quasistatic_row

  !> A snapshot of a quasi-static run: displacements and stresses.
  subroutine quasistatic_snapshot(deck, record, name, label, time, u, stress)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: name, label
    real(dp), intent(in) :: time, u(:), stress(:, :, :)
    type(snapshot_t) :: snapshot
    snapshot%name = name
    snapshot%label = label
    snapshot%time = time
    snapshot%displacement = nodal_field(deck%mesh, u)
    call set_snapshot_stress(deck%mesh, stress, snapshot)
    call record_add_snapshot(record, snapshot)
  end subroutine quasistatic_snapshot

  !> Nodal stress at one node: Gauss values extrapolated in each element that
  !> has the node, then averaged (the same recovery as nodal_average).
  function node_stress(mesh, stress, node) result(value)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: stress(:, :, :)
    integer, intent(in) :: node
    real(dp) :: value(4)
    value = corner_stress(stress, node_corners(mesh, node))
  end function node_stress

  !> The (corner, element) pairs of the elements that meet at a node: a
  !> search over the mesh, done once so that corner_stress is O(1) per step.
  pure function node_corners(mesh, node) result(corners)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: node
    integer, allocatable :: corners(:, :)
    integer :: e, a, number
    number = count(mesh%connectivity == node)
    allocate(corners(2, number))
    number = 0
    do e = 1, mesh%nelem
      do a = 1, 4
        if (mesh%connectivity(a, e) /= node) cycle
        number = number + 1
        corners(:, number) = [a, e]
      end do
    end do
  end function node_corners

  !> The nodal stress at a node from its corners (node_corners): the bilinear
  !> extrapolation of each element's Gauss stresses, averaged over the elements.
  pure function corner_stress(stress, corners) result(value)
    real(dp), intent(in) :: stress(:, :, :)
    integer, intent(in) :: corners(:, :)
    real(dp) :: value(4)
    real(dp) :: extrapolation(4, 4)
    integer :: k
    extrapolation = gauss_to_node_extrapolation()
    value = 0.0_dp
    do k = 1, size(corners, 2)
      value = value + matmul(stress(:, :, corners(2, k)), extrapolation(:, corners(1, k)))
    end do
    value = value/max(size(corners, 2), 1)
  end function corner_stress

  !> The stress fields of a snapshot from Gauss-point stresses: the Gauss
  !> values, their nodal averages, and the nodal maximum shear and von Mises stress.
  subroutine set_snapshot_stress(mesh, stress, snapshot)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: stress(:, :, :)
    type(snapshot_t), intent(inout) :: snapshot
    snapshot%stress_gauss = stress
    snapshot%stress = nodal_average(mesh, stress)
    snapshot%max_shear = max_shear(snapshot%stress(1, :), snapshot%stress(2, :), snapshot%stress(3, :), &
                                   snapshot%stress(4, :))
    snapshot%von_mises = von_mises(snapshot%stress(1, :), snapshot%stress(2, :), snapshot%stress(3, :), &
                                   snapshot%stress(4, :))
  end subroutine set_snapshot_stress

  !> Summary of a state: largest displacement, extreme stresses over the Gauss
  !> points. `prefix` (default none) names the state, e.g. 'end_'.
  subroutine put_field_summary(displacement, stress, record, prefix)
    real(dp), intent(in) :: displacement(:, :), stress(:, :, :)
    type(record_t), intent(inout) :: record
    character(*), intent(in), optional :: prefix
    character(:), allocatable :: p
    p = ''
    if (present(prefix)) p = prefix
    associate (s => stress)
    call record_put_real(record, p//'max_displacement_m', maxval(norm2(displacement, dim=1)))
    call record_put_real(record, p//'sigma_r_min_Pa', minval(s(1, :, :)))
    call record_put_real(record, p//'sigma_r_max_Pa', maxval(s(1, :, :)))
    call record_put_real(record, p//'sigma_z_min_Pa', minval(s(2, :, :)))
    call record_put_real(record, p//'sigma_z_max_Pa', maxval(s(2, :, :)))
    call record_put_real(record, p//'sigma_theta_min_Pa', minval(s(3, :, :)))
    call record_put_real(record, p//'sigma_theta_max_Pa', maxval(s(3, :, :)))
    call record_put_real(record, p//'tau_rz_max_abs_Pa', maxval(abs(s(4, :, :))))
    call record_put_real(record, p//'von_mises_max_Pa', maxval(von_mises(s(1, :, :), s(2, :, :), s(3, :, :), &
                                                                           s(4, :, :))))
    call record_put_real(record, p//'max_shear_max_Pa', maxval(max_shear(s(1, :, :), s(2, :, :), s(3, :, :), &
                                                                           s(4, :, :))))
    end associate
  end subroutine put_field_summary

  !> Summary keys probe_<name>_{r_m, z_m, ur_m, uz_m, sr_Pa, sz_Pa, st_Pa, trz_Pa} of a state.
  subroutine put_probe_summary(deck, displacement, stress, record)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: displacement(:, :), stress(:, :, :)
    type(record_t), intent(inout) :: record
    integer :: p, node, c
    character(len=6), parameter :: probe_columns(6) = ['ur_m  ', 'uz_m  ', 'sr_Pa ', 'sz_Pa ', 'st_Pa ', 'trz_Pa']
    do p = 1, size(deck%probes)
      node = deck%probes(p)%node
      call record_put_real(record, 'probe_'//deck%probes(p)%name//'_r_m', deck%mesh%xy(1, node))
      call record_put_real(record, 'probe_'//deck%probes(p)%name//'_z_m', deck%mesh%xy(2, node))
      associate (values => [displacement(:, node), node_stress(deck%mesh, stress, node)])
      do c = 1, 6
        call record_put_real(record, 'probe_'//deck%probes(p)%name//'_'//trim(probe_columns(c)), values(c))
      end do
      end associate
    end do
  end subroutine put_probe_summary

  !> n as a six-digit, zero-padded text (snapshot names sort in time order).
  pure function zero_padded(n) result(text)
    integer, intent(in) :: n
    character(len=6) :: text
    write(text, '(i6.6)') n
  end function zero_padded
end module visco2d_static
