!> The legacy base: static linear analysis S U = R (eq. [25] without inertia).
!> Assemble, impose supports, factor once (dpbtrf), back-substitute (dpbtrs),
!> recover strains and stresses at the Gauss points and at the nodes.
module visco2d_static
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: itoa
  use visco2d_deck, only: deck_t
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: stress_from_strain, von_mises, max_shear
  use visco2d_element, only: element_strains
  use visco2d_banded, only: band_matrix_t, band_constrain, band_factor, band_solve, band_multiply
  use visco2d_assembly, only: assemble_stiffness, external_load, support_mask, node_dof, gather, nodal_average
  use visco2d_record, only: record_t, snapshot_t, record_put_real, history_define, history_append, &
                            record_add_snapshot
  implicit none
  private

  public :: static_solution_t, solve_static, static_record, singular_message

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

  !> Solve the static problem of a deck.
  subroutine solve_static(deck, solution, error)
    type(deck_t), intent(in) :: deck
    type(static_solution_t), intent(out) :: solution
    type(error_t), allocatable, intent(out) :: error
    type(band_matrix_t) :: stiffness, constrained
    real(dp), allocatable :: shear(:), bulk(:), load(:), u(:), zero(:)
    logical, allocatable :: fixed(:)
    integer :: e, info, node

    associate (mesh => deck%mesh)
    shear = deck%materials(mesh%element_material)%shear
    bulk = deck%materials(mesh%element_material)%bulk
    call assemble_stiffness(deck, shear, bulk, stiffness)
    load = external_load(deck, 1.0_dp)
    fixed = support_mask(deck)
    allocate(zero(size(load)))
    zero = 0.0_dp
    u = load
    constrained = stiffness
    call band_constrain(constrained, fixed, zero, u)
    call band_factor(constrained, info)
    if (info > 0) then
      call set_error(error, singular_message(deck, info), file=deck%cards%file)
      return
    end if
    call band_solve(constrained, u)

    allocate(solution%displacement(2, mesh%nnode), solution%reaction(2, mesh%nnode))
    do node = 1, mesh%nnode
      solution%displacement(:, node) = u(node_dof(mesh, node, 1):node_dof(mesh, node, 2))
    end do
    associate (residual => band_multiply(stiffness, u) - load)
    do node = 1, mesh%nnode
      solution%reaction(:, node) = residual(node_dof(mesh, node, 1):node_dof(mesh, node, 2))
    end do
    solution%strain_energy = 0.5_dp*dot_product(u, residual + load)
    end associate
    solution%external_work = 0.5_dp*dot_product(load, u)

    allocate(solution%strain(4, 4, mesh%nelem), solution%stress(4, 4, mesh%nelem))
    do e = 1, mesh%nelem
      solution%strain(:, :, e) = element_strains(deck%geometry, mesh%xy(:, mesh%connectivity(:, e)), gather(mesh, e, u))
      do info = 1, 4
        solution%stress(:, info, e) = stress_from_strain(shear(e), bulk(e), solution%strain(:, info, e))
      end do
    end do
    solution%nodal_stress = nodal_average(mesh, solution%stress)
    end associate
  end subroutine solve_static

  !> Message for a factorization failure at band equation `equation`.
  function singular_message(deck, equation) result(message)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    character(:), allocatable :: message
    integer :: node, position
    character(len=3) :: component
    position = (equation - 1)/2 + 1
    component = merge('u_r', 'u_z', mod(equation, 2) == 1)
    message = 'the stiffness matrix is singular or not positive definite'
    do node = 1, deck%mesh%nnode
      if (deck%mesh%equation(node) == position) then
        message = message//' at node '//itoa(deck%mesh%node_id(node))//' ('//component//')'
        exit
      end if
    end do
    message = message//': the body can probably move freely (a rigid-body mode); add FIX cards'// &
      ' that stop it, or check the material constants'
  end function singular_message

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

    associate (mesh => deck%mesh, s => solution%stress)
    call record_put_real(record, 'max_displacement_m', maxval(norm2(solution%displacement, dim=1)))
    call record_put_real(record, 'sigma_r_min_Pa', minval(s(1, :, :)))
    call record_put_real(record, 'sigma_r_max_Pa', maxval(s(1, :, :)))
    call record_put_real(record, 'sigma_z_min_Pa', minval(s(2, :, :)))
    call record_put_real(record, 'sigma_z_max_Pa', maxval(s(2, :, :)))
    call record_put_real(record, 'sigma_theta_min_Pa', minval(s(3, :, :)))
    call record_put_real(record, 'sigma_theta_max_Pa', maxval(s(3, :, :)))
    call record_put_real(record, 'tau_rz_max_abs_Pa', maxval(abs(s(4, :, :))))
    call record_put_real(record, 'von_mises_max_Pa', maxval(von_mises(s(1, :, :), s(2, :, :), s(3, :, :), s(4, :, :))))
    call record_put_real(record, 'max_shear_max_Pa', maxval(max_shear(s(1, :, :), s(2, :, :), s(3, :, :), s(4, :, :))))
    call record_put_real(record, 'strain_energy_J', solution%strain_energy)
    call record_put_real(record, 'external_work_J', solution%external_work)
    call record_put_real(record, 'reaction_r_N', sum(solution%reaction(1, :)))
    call record_put_real(record, 'reaction_z_N', sum(solution%reaction(2, :)))

    columns = [character(len=48) :: 'step', 't_s', 'max_displacement_m', 'strain_J', 'work_J']
    row = [1.0_dp, 0.0_dp, maxval(norm2(solution%displacement, dim=1)), solution%strain_energy, &
           solution%external_work]
    do k = 1, size(deck%probes)
      node = deck%probes(k)%node
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_r_m', mesh%xy(1, node))
      call record_put_real(record, 'probe_'//deck%probes(k)%name//'_z_m', mesh%xy(2, node))
      associate (values => [solution%displacement(:, node), solution%nodal_stress(:, node)])
      do c = 1, 6
        call record_put_real(record, 'probe_'//deck%probes(k)%name//'_'//trim(probe_columns(c)), values(c))
        columns = [character(len=48) :: columns, deck%probes(k)%name//'_'//trim(probe_columns(c))]
      end do
      row = [row, values]
      end associate
    end do
    call history_define(record, columns, 1)
    call history_append(record, row)

    snapshot%name = 'step_000001'
    snapshot%label = 'static'
    snapshot%time = 0.0_dp
    snapshot%displacement = solution%displacement
    snapshot%stress = solution%nodal_stress
    snapshot%stress_gauss = solution%stress
    snapshot%max_shear = max_shear(solution%nodal_stress(1, :), solution%nodal_stress(2, :), &
                                   solution%nodal_stress(3, :), solution%nodal_stress(4, :))
    snapshot%von_mises = von_mises(solution%nodal_stress(1, :), solution%nodal_stress(2, :), &
                                   solution%nodal_stress(3, :), solution%nodal_stress(4, :))
    call record_add_snapshot(record, snapshot)
    end associate
  end subroutine static_record
end module visco2d_static
