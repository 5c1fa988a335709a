!> The legacy base: static linear analysis S U = R (eq. [25] without inertia).
!> Assemble, impose supports, factor once (visco2d_factor), back-substitute
!> once, recover strains and stresses at the Gauss points and the nodes. The
!> legacy program's quasi-static time loop is visco2d_quasistatic; the
!> located errors of a failed solve are visco2d_solve_errors.
module visco2d_static
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, whole_body_factor, energy_basis
  use visco2d_error, only: error_t, set_error
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: material_t, stress_from_strain
  use visco2d_model, only: settings_t, loads_t, probe_t, source_t
  use visco2d_element, only: element_strains
  use visco2d_banded, only: band_matrix_t, band_multiply, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card, solve_failure_text
  use visco2d_assembly, only: assemble_stiffness, external_load, support_mask, gather, nodal_average, &
                              prescribed_displacement, gravity_load, nodal_field
  use visco2d_record, only: record_t, snapshot_t, record_put, record_put_real, history_define, &
                            history_append, record_add_snapshot
  use visco2d_solve_errors, only: check_balance, singular_error, not_finite_error
  use visco2d_field_summary, only: set_snapshot_stress, put_field_summary, put_probe_summary
  implicit none
  private

  public :: static_solution_t, solve_static, static_record

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

  !> Solve the static problem of a mesh of these materials under these
  !> supports and loads (at t = 0); `source` locates a failure in the input
  !> file. `extra_fixed` / `extra_values` prescribe further displacements
  !> (the contact extension's plate nodes); `given` is a displacement solved
  !> by the caller, of which only the reactions, energies, strains and
  !> stresses are computed.
  subroutine solve_static(mesh, materials, settings, loads, source, solution, error, extra_fixed, extra_values, given)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    type(source_t), intent(in) :: source
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

    shear = materials(mesh%element_material)%shear
    bulk = materials(mesh%element_material)%bulk
    call assemble_stiffness(mesh, settings, shear, bulk, stiffness)
    load = external_load(mesh, settings, loads, 0.0_dp) + gravity_load(mesh, settings, materials, loads)
    fixed = support_mask(mesh, settings, loads)
    zero = prescribed_displacement(mesh, loads, 0.0_dp)
    if (present(extra_fixed) .and. present(extra_values)) then
      zero = merge(extra_values, zero, extra_fixed)
      fixed = fixed .or. extra_fixed
    end if
    if (present(given)) then                       ! a constrained solve done by the caller (a PAD's contact)
      u = given
    else
      u = load
      call band_constrain_rhs(stiffness, fixed, zero, u)
      call factor_compute(factor, stiffness, fixed, info, solver_of_card(settings%solver))
      if (info > 0) then
        call singular_error(mesh, source, info, error)
        return
      end if
      call factor_solve(factor, u, info)
      if (info /= 0) then
        call set_error(error, solve_failure_text(info))   ! located by the driver
        return
      end if
    end if
    if (.not. all(ieee_is_finite(u))) then
      call not_finite_error(source, 'the static displacement', error)
      return
    end if
    if (.not. present(given)) then
      call check_balance(mesh, source, band_multiply(stiffness, u) - load, fixed, load, error)
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
      solution%strain(:, :, e) = element_strains(settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), &
                                                 gather(mesh, e, u), settings%formulation)
      do info = 1, 4
        solution%stress(:, info, e) = stress_from_strain(shear(e), bulk(e), solution%strain(:, info, e))
      end do
    end do
    solution%nodal_stress = nodal_average(mesh, solution%stress)
    if (.not. all(ieee_is_finite(solution%stress)) .or. .not. all(ieee_is_finite(solution%reaction)) .or. &
        .not. ieee_is_finite(solution%strain_energy) .or. .not. ieee_is_finite(solution%external_work)) &
      call not_finite_error(source, 'the static stress, reaction or energy', error)
  end subroutine solve_static

  !> Summary, one-row history and the final snapshot of a static solution.
  !> The body is the first `body_nodes` nodes and `body_elements` elements
  !> (default: all; a PAD's mesh comes after them): the field summary is of
  !> the body alone.
  subroutine static_record(mesh, settings, probes, solution, record, body_nodes, body_elements)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    type(probe_t), intent(in) :: probes(:)
    type(static_solution_t), intent(in) :: solution
    type(record_t), intent(inout) :: record
    integer, intent(in), optional :: body_nodes, body_elements
    type(snapshot_t) :: snapshot
    character(len=48), allocatable :: columns(:)
    real(dp), allocatable :: row(:)
    integer :: k, node, c, nodes, elements
    character(len=6), parameter :: probe_columns(6) = ['ur_m  ', 'uz_m  ', 'sr_Pa ', 'sz_Pa ', 'st_Pa ', 'trz_Pa']

    nodes = mesh%nnode
    if (present(body_nodes)) nodes = body_nodes
    elements = mesh%nelem
    if (present(body_elements)) elements = body_elements
    call put_field_summary(solution%displacement(:, :nodes), solution%stress(:, :, :elements), record)
    ! Energies and reactions on the energy_basis (whole body in axisymmetry).
    associate (factor => whole_body_factor(settings%geometry))
    call record_put(record, 'energy_basis', energy_basis(settings%geometry))
    call record_put_real(record, 'strain_energy_J', factor*solution%strain_energy)
    call record_put_real(record, 'external_work_J', factor*solution%external_work)
    call record_put_real(record, 'reaction_r_N', factor*sum(solution%reaction(1, :)))
    call record_put_real(record, 'reaction_z_N', factor*sum(solution%reaction(2, :)))

    columns = [character(len=48) :: 'step', 't_s', 'max_displacement_m', 'strain_J', 'work_J']
    row = [1.0_dp, 0.0_dp, maxval(norm2(solution%displacement, dim=1)), factor*solution%strain_energy, &
           factor*solution%external_work]
    end associate
    call put_probe_summary(mesh, probes, solution%displacement, solution%stress, record)
    do k = 1, size(probes)
      node = probes(k)%node
      do c = 1, 6
        columns = [character(len=48) :: columns, probes(k)%name//'_'//trim(probe_columns(c))]
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
  end subroutine static_record

end module visco2d_static
