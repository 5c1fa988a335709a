!> ANALYSIS STATIC of a deck with a PLASTIC material: the loads (pressures,
!> point loads, gravity and prescribed displacements, all proportional)
!> applied in `settings%increments` equal increments, each iterated to
!> equilibrium by a full Newton method with the consistent tangent of the
!> return mapping (visco2d_plasticity: Simo and Hughes 1998, Box 3.2).
!>
!> In increment k the load is lambda_k R, lambda_k = k/N. Newton iteration i
!> solves K_t du = R_k - F(u) (the prescribed displacements' increment taken
!> in the first iteration), K_t = sum_e sum_gp B^T C_gp B |J| r assembled
!> from the tangents C_gp of the last stress evaluation (the elastic matrix
!> where a point is elastic or its material has no PLASTIC card). Each
!> Gauss point's stress is the radial return from the increment's start:
!> s_trial = s_n + 2 G dev(de), p = p_n + K tr(de). An increment has
!> converged when both
!>   |r|  <= force_tolerance  max(|R_k|, |F(u)|)   (free equations; F holds the reactions)
!>   |r . K_t^-1 r| <= energy_tolerance |du_1 . r_0|   (the energy norm of the next correction,
!>                                                     relative to the first iteration's)
!> hold; after `settings%iterations` (ITERATIONS=, default 30) a located error (the ANALYSIS card, the
!> increment, the iteration, both residuals) is returned, never a result.
!>
!> Energies (per radian in axisymmetry, as visco2d_static's): the external
!> work is the trapezoidal sum of 1/2 (P_(k-1) + P_k) . (u_k - u_(k-1)) over the
!> increments, P the applied load lambda_k R on the free equations and the
!> reactions on the supported ones; the stored elastic energy
!> int (p^2/(2K) + s:s/(4G)) dV; the plastic dissipation the same rule's
!> int 1/2 (s_(k-1) + s_k) : de_p dV. The trapezoid on sigma : de splits
!> exactly into the elastic and the plastic parts, so W - U - D is the work
!> of the out-of-balance forces left by Newton: the balance W = U + D holds
!> to the force tolerance.
!> The kernel's backward value s_k : de_p (return_result_t%dissipation) is
!> summed too, as `dissipation_backward`: it differs from D by O(1/N).
module visco2d_plastic_static
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, whole_body_factor
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, short_real
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: material_t, elastic_matrix, stress_from_strain
  use visco2d_model, only: settings_t, loads_t, source_t
  use visco2d_element, only: element_b_matrices, gauss_count
  use visco2d_banded, only: band_matrix_t, band_constrain_rhs, band_multiply
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card, solve_failure_text, correction_energy
  use visco2d_assembly, only: element_dofs, assemble_point_tangents, external_load, gravity_load, support_mask, &
                              prescribed_displacement, &
                              scatter_add, nodal_field, nodal_average, node_dof
  use visco2d_static, only: static_solution_t
  use visco2d_solve_errors, only: singular_error, not_finite_error, analysis_error
  use visco2d_plasticity, only: return_result_t, consistent_tangent, deviatoric_norm, viscoplastic_update
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients
  use visco2d_record, only: record_t, record_put_integer, record_put_real
  implicit none
  private

  public :: plastic_summary_t, plastic_plate_t, solve_plastic_static, plastic_record, any_plastic
  public :: force_tolerance, energy_tolerance

  real(dp), parameter :: force_tolerance = 1.0e-8_dp    !< |r| relative to the load (and reactions)
  real(dp), parameter :: energy_tolerance = 1.0e-16_dp  !< |r . K^-1 r| relative to the first iteration's

  !> A rigid plate under the body (ANALYSIS STATIC with a PLATE SLIP):
  !> frictionless contact, a node on it held at u_z = Z - z, freed when its
  !> reaction pulls. `active` holds the nodes on it at the start (those
  !> within `tolerance`), and at the end on return.
  type :: plastic_plate_t
    real(dp) :: z = 0.0_dp                   !< the plate's height Z, m
    real(dp) :: tolerance = 0.0_dp           !< a node through the plate by more than this is put on it, m
    integer, allocatable :: candidates(:)    !< the nodes that may touch it
    logical, allocatable :: active(:)        !< (nnode) on the plate
  end type plastic_plate_t

  !> What a plastic static solve adds to the static solution.
  type :: plastic_summary_t
    integer :: increments = 0                       !< load increments N
    integer :: iterations = 0                       !< Newton iterations, all increments
    integer :: iterations_max = 0                   !< the most in one increment
    integer, allocatable :: increment_iterations(:) !< (N) Newton iterations per increment
    real(dp), allocatable :: force_residual(:, :)   !< (ITERATIONS, N) |r| / max(|R_k|, |F|) after each iteration
    real(dp), allocatable :: equivalent_plastic(:, :) !< (gauss_count, nelem) ebar at the end
    real(dp) :: equivalent_plastic_max = 0.0_dp     !< max ebar
    real(dp) :: dissipation = 0.0_dp                !< plastic dissipation D (trapezoidal), J (per radian in axisymmetry)
    real(dp) :: dissipation_backward = 0.0_dp       !< sum s_k : de_p dV, J (the kernel's backward rule)
    real(dp) :: yielded_volume = 0.0_dp             !< int over the points with ebar > 0, m^3 (per radian in axisymmetry)
    integer :: contact_changes = 0                  !< changes of the contact set (a PLATE), all increments
  end type plastic_summary_t

contains

  !> True if a material of the deck has a PLASTIC card.
  pure logical function any_plastic(materials)
    type(material_t), intent(in) :: materials(:)
    integer :: k
    any_plastic = .false.
    do k = 1, size(materials)
      if (materials(k)%plastic) any_plastic = .true.
    end do
  end function any_plastic

  !> The load-incremented Newton solve of a static deck with plasticity
  !> (module comment): the static solution (displacement, reactions, Gauss
  !> strains and stresses, stored energy and external work) and the summary.
  !>
  !> With a `plate`, each increment's Newton solve holds the contact nodes'
  !> u_z at Z - z (an active set): once it has converged, the free
  !> candidates through the plate by more than the tolerance are put on it
  !> and the contact nodes whose reaction pulls (F_int - F_ext < 0 in z)
  !> are freed, and Newton goes on from where it is (every Gauss point is
  !> still returned from the increment's start, so the converged state is
  !> that of the final set) until the set holds: no free node through the
  !> plate, every contact node pushing. If the count of such nodes has not
  !> fallen after 10 changes of whole blocks, the set changes by the one
  !> worst node at a time (Judice and Pires); after 50 + 10 x candidates
  !> changes in one increment, a located error.
  subroutine solve_plastic_static(mesh, materials, settings, loads, source, solution, summary, error, plate)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    type(source_t), intent(in) :: source
    type(static_solution_t), intent(out) :: solution
    type(plastic_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(plastic_plate_t), intent(inout), optional :: plate
    real(dp), allocatable :: b(:, :, :, :), weight(:, :), tangent(:, :, :, :)
    real(dp), allocatable :: stress(:, :, :), strain(:, :, :), ebar(:, :)          ! committed
    real(dp), allocatable :: trial_stress(:, :, :), trial_strain(:, :, :), trial_ebar(:, :), plastic(:, :, :)
    real(dp), allocatable :: load(:), presc(:), u(:), u_start(:), du(:), rhs(:), force(:), force_start(:), r(:)
    real(dp), allocatable :: step_backward(:, :)
    type(step_coefficients_t), allocatable :: instant(:)   !< per material at dt = 0: mu = G(0), K
    logical, allocatable :: fixed(:), supports(:)
    logical, allocatable :: freed(:)                 !< (candidates) freed from the plate in this increment
    real(dp), allocatable :: target(:)
    type(band_matrix_t) :: stiffness
    type(factor_t) :: factor
    real(dp) :: lambda, energy_first, energy_next, force_ratio, scale
    integer :: nelem, e, k, iteration, info, n, max_iterations, changes, strikes, best_violations, violations
    integer :: increment_iterations
    logical :: converged, first

    nelem = mesh%nelem
    allocate(instant(size(materials)))
    do e = 1, size(materials)
      instant(e) = step_coefficients(materials(e), 0.0_dp)
    end do
    n = settings%increments
    max_iterations = settings%iterations
    allocate(b(4, 8, gauss_count, nelem), weight(gauss_count, nelem), tangent(4, 4, gauss_count, nelem))
    do e = 1, nelem
      call element_b_matrices(settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), b(:, :, :, e), weight(:, e), &
                              settings%formulation)
      associate (m => materials(mesh%element_material(e)))
      do k = 1, gauss_count
        tangent(:, :, k, e) = elastic_matrix(m%shear, m%bulk)
      end do
      end associate
    end do
    allocate(stress(4, gauss_count, nelem), strain(4, gauss_count, nelem), ebar(gauss_count, nelem))
    allocate(plastic(4, gauss_count, nelem), step_backward(gauss_count, nelem))
    stress = 0.0_dp
    strain = 0.0_dp
    ebar = 0.0_dp
    trial_stress = stress
    trial_strain = strain
    trial_ebar = ebar
    load = external_load(mesh, settings, loads, 0.0_dp) + gravity_load(mesh, settings, materials, loads)
    supports = support_mask(mesh, settings, loads)
    fixed = supports
    presc = prescribed_displacement(mesh, loads, 0.0_dp)
    allocate(u(2*mesh%nnode), force(2*mesh%nnode))
    u = 0.0_dp
    force = 0.0_dp
    summary%increments = n
    allocate(summary%increment_iterations(n), summary%force_residual(max_iterations, n))
    summary%increment_iterations = 0
    summary%force_residual = 0.0_dp
    solution%external_work = 0.0_dp

    do k = 1, n
      lambda = real(k, dp)/real(n, dp)
      u_start = u
      force_start = force
      changes = 0
      strikes = 0
      best_violations = huge(1)
      increment_iterations = 0
      if (present(plate)) freed = spread(.false., 1, size(plate%candidates))
      if (present(plate)) then
        call predict_contact_set()
        if (allocated(error)) return
      end if
      contact_set: do
      call held_equations()
      energy_first = 0.0_dp
      converged = .false.
      first = .true.                                   ! this iteration takes the held values' increment
      do iteration = 1, max_iterations
        call assemble_point_tangents(mesh, b, weight, tangent, stiffness)   ! K_t of the last evaluation
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
              'the tangent stiffness is singular in load increment '//integer_text(k)//' of '//integer_text(n)// &
              ' (Newton iteration '//integer_text(iteration)//', equation '//integer_text(info) &
                //'): the load is probably above '// &
              'the limit load of the perfectly plastic body (give a hardening TANGENT= or SLOPE=, or less load)')
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
        u = u + du
        call evaluate(u - u_start)
        r = lambda*load - force
        scale = max(norm2(lambda*load), norm2(force), tiny(1.0_dp))
        force_ratio = norm2(merge(0.0_dp, r, fixed))/scale
        summary%force_residual(iteration, k) = force_ratio
        if (.not. (ieee_is_finite(force_ratio) .and. all(ieee_is_finite(u)))) then
          call analysis_error(source, error, &
            'the plastic static solve diverged in load increment '//integer_text(k)//' of '//integer_text(n)// &
            ' (Newton iteration '//integer_text(iteration)//': the displacement or the residual is not finite)')
          return
        end if
        if (present(plate)) then                       ! nodes through the plate are put on it at once
          if (put_on_plate() > 0) then
            call held_equations()
            first = .true.
            cycle
          end if
        end if
        call correction_energy(factor, r, fixed, energy_next, info)   ! the next correction's, with this factor
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
        call analysis_error(source, error, &
          'the plastic static solve did not converge in load increment '//integer_text(k)//' of '// &
          integer_text(n)//': after '//integer_text(max_iterations)//' Newton iterations the force residual is '// &
          short_real(force_ratio)//' of the load (tolerance '//short_real(force_tolerance)//') and the energy '// &
          'norm '//short_real(energy_next/max(energy_first, tiny(1.0_dp)))//' of the first iteration''s '// &
          '(tolerance '//short_real(energy_tolerance)//'): the load may be above the limit load; give more '// &
          'INCREMENTS= (or ITERATIONS=) or a hardening TANGENT=')
        return
      end if
      increment_iterations = increment_iterations + iteration
      if (.not. present(plate)) exit contact_set
      call change_contact_set(violations)
      if (allocated(error)) return
      if (violations == 0) exit contact_set
      end do contact_set
      summary%increment_iterations(k) = increment_iterations
      summary%iterations = summary%iterations + increment_iterations
      summary%iterations_max = max(summary%iterations_max, increment_iterations)
      ! Commit: the trapezoidal work and dissipation of the increment (module comment).
      solution%external_work = solution%external_work + 0.5_dp*dot_product( &
        merge(force_start, (lambda - 1.0_dp/n)*load, fixed) + merge(force, lambda*load, fixed), u - u_start)
      do e = 1, nelem
        do info = 1, gauss_count
          associate (s_start => deviator(stress(:, info, e)), s_end => deviator(trial_stress(:, info, e)))
          summary%dissipation = summary%dissipation + weight(info, e)*0.5_dp* &
            contract(s_start + s_end, plastic(:, info, e))
          end associate
          summary%dissipation_backward = summary%dissipation_backward + weight(info, e)*step_backward(info, e)
        end do
      end do
      stress = trial_stress
      strain = trial_strain
      ebar = trial_ebar
    end do

    solution%displacement = nodal_field(mesh, u)
    solution%reaction = nodal_field(mesh, force - load)
    solution%strain = strain
    solution%stress = stress
    solution%nodal_stress = nodal_average(mesh, stress)
    solution%strain_energy = 0.0_dp
    do e = 1, nelem
      associate (m => materials(mesh%element_material(e)))
      do info = 1, gauss_count
        solution%strain_energy = solution%strain_energy + weight(info, e)*( &
          (sum(stress(1:3, info, e))/3.0_dp)**2/(2.0_dp*m%bulk) + &
          deviatoric_norm(deviator(stress(:, info, e)))**2/(4.0_dp*m%shear))
      end do
      end associate
    end do
    summary%equivalent_plastic = ebar
    summary%equivalent_plastic_max = maxval(ebar)
    summary%yielded_volume = sum(weight, mask=ebar > 0.0_dp)
    if (.not. all(ieee_is_finite(solution%stress)) .or. .not. ieee_is_finite(solution%strain_energy) .or. &
        .not. ieee_is_finite(solution%external_work)) &
      call not_finite_error(source, 'the plastic static stress or energy', error)

  contains

    !> The held equations and their values at load factor lambda: the
    !> supports (lambda times the prescribed values) and, with a plate, u_z of
    !> every contact node at Z - z.
    subroutine held_equations()
      integer :: i, dof
      fixed = supports
      target = lambda*presc
      if (.not. present(plate)) return
      do i = 1, size(plate%candidates)
        if (.not. plate%active(plate%candidates(i))) cycle
        dof = node_dof(mesh, plate%candidates(i), 2)
        if (supports(dof)) cycle
        fixed(dof) = .true.
        target(dof) = plate%z - mesh%xy(2, plate%candidates(i))
      end do
    end subroutine held_equations

    !> The contact set an increment starts from: the linear contact problem
    !> of the predictor (the tangent of the last converged state) solved with
    !> the set changed as after a Newton solve (change_contact_set: the free
    !> candidates it puts through the plate held, the contact nodes it makes
    !> pull freed), until it holds or 50 + 10 x candidates solves have
    !> passed. Newton then starts at the set of the linearised increment:
    !> from a set too small (a body on its pole node alone) the first iterate
    !> dents the flesh far into the plastic range, and the tangent of that
    !> state does not find its way back.
    subroutine predict_contact_set()
      real(dp), allocatable :: predicted(:), reaction(:)
      integer :: pass, predictor_strikes, predictor_best, changed
      call assemble_point_tangents(mesh, b, weight, tangent, stiffness)   ! K_t of the last evaluation
      predictor_strikes = 0
      predictor_best = huge(1)
      do pass = 1, 50 + 10*size(plate%candidates)
        call held_equations()
        rhs = lambda*load - force
        call band_constrain_rhs(stiffness, fixed, target - u, rhs)
        call factor_compute(factor, stiffness, fixed, info, solver_of_card(settings%solver))
        if (info > 0) then
          if (k == 1 .and. pass == 1) then
            call singular_error(mesh, source, info, error)
          else
            call analysis_error(source, error, &
              'the tangent stiffness is singular in load increment '//integer_text(k)//' of '// &
              integer_text(n)//' (the contact predictor, equation '//integer_text(info)//')')
          end if
          return
        end if
        call factor_solve(factor, rhs, info)
        if (info /= 0) then
          call set_error(error, solve_failure_text(info))     ! located by the driver
          return
        end if
        predicted = u + rhs
        reaction = force + band_multiply(stiffness, rhs) - lambda*load   ! linearised F_int - F_ext
        call contact_violations(predicted, reaction, changed, predictor_best, predictor_strikes)
        if (changed == 0) exit
      end do
    end subroutine predict_contact_set

    !> During a Newton solve with a plate: the free candidates through it by
    !> more than the tolerance put on it (a point-held body would otherwise
    !> iterate to a deep plastic dent first), except those freed in this
    !> increment (the iterates on the way would put them back before the
    !> solve shows where they go); their count.
    integer function put_on_plate() result(added)
      integer :: i, node, dof
      added = 0
      do i = 1, size(plate%candidates)
        node = plate%candidates(i)
        dof = node_dof(mesh, node, 2)
        if (plate%active(node) .or. supports(dof) .or. freed(i)) cycle
        if (plate%z - (mesh%xy(2, node) + u(dof)) <= plate%tolerance) cycle
        plate%active(node) = .true.
        added = added + 1
      end do
      summary%contact_changes = summary%contact_changes + min(added, 1)
    end function put_on_plate

    !> After a converged Newton solve with a plate: the set changed
    !> (contact_violations on the solution), or a located error when it has
    !> changed 50 + 10 x candidates times in the increment.
    subroutine change_contact_set(violations)
      integer, intent(out) :: violations
      call contact_violations(u, force - lambda*load, violations, best_violations, strikes)
      if (violations == 0) return
      changes = changes + 1
      if (changes > 50 + 10*size(plate%candidates)) then
        call analysis_error(source, error, &
          'the contact set on the PLATE does not settle in load increment '//integer_text(k)// &
          ' of '//integer_text(n)//' ('//integer_text(changes - 1)//' changes, '//integer_text(violations)// &
          ' node(s) still through the plate or pulling): give more INCREMENTS=')
      end if
    end subroutine change_contact_set

    !> For a displacement and its reactions F_int - F_ext: the free
    !> candidates through the plate by more than the tolerance and the
    !> contact nodes that pull (a z reaction below -1e-6 of the largest
    !> contact reaction, as check_settled), `violations` of them, all
    !> changed; if their count has not fallen (below `best`) in 10 changes
    !> (`strikes`), the worst one alone (Judice and Pires).
    subroutine contact_violations(displacement, reaction, violations, best, strikes)
      real(dp), intent(in) :: displacement(:), reaction(:)
      integer, intent(out) :: violations
      integer, intent(inout) :: best, strikes
      real(dp) :: worst, amount, reaction_scale
      integer :: i, node, dof, worst_node
      logical, allocatable :: change(:)
      allocate(change(size(plate%candidates)))
      change = .false.
      reaction_scale = tiny(1.0_dp)
      do i = 1, size(plate%candidates)
        dof = node_dof(mesh, plate%candidates(i), 2)
        if (plate%active(plate%candidates(i))) reaction_scale = max(reaction_scale, abs(reaction(dof)))
      end do
      reaction_scale = 1.0e-6_dp*reaction_scale
      worst = 0.0_dp
      worst_node = 0
      do i = 1, size(plate%candidates)
        node = plate%candidates(i)
        dof = node_dof(mesh, node, 2)
        if (supports(dof)) cycle
        if (plate%active(node)) then                   ! pulls: F_int - F_ext < 0 in z (the plate lies below)
          amount = -reaction(dof)
          change(i) = amount > reaction_scale
          amount = amount/reaction_scale
        else                                          ! through the plate
          amount = plate%z - (mesh%xy(2, node) + displacement(dof))
          change(i) = amount > plate%tolerance
          amount = amount/max(plate%tolerance, tiny(1.0_dp))
        end if
        if (change(i) .and. amount > worst) then
          worst = amount
          worst_node = i
        end if
      end do
      violations = count(change)
      if (violations == 0) return
      summary%contact_changes = summary%contact_changes + 1
      if (violations < best) then
        best = violations
        strikes = 0
      else
        strikes = strikes + 1
      end if
      if (strikes >= 10) then                          ! one node at a time: the worst
        change = .false.
        change(worst_node) = .true.
      end if
      do i = 1, size(plate%candidates)
        if (.not. change(i)) cycle
        plate%active(plate%candidates(i)) = .not. plate%active(plate%candidates(i))
        if (.not. plate%active(plate%candidates(i))) freed(i) = .true.
      end do
    end subroutine contact_violations

    !> Stresses, tangents and the internal force at u = u_start + increment:
    !> every Gauss point's return from the increment's start.
    subroutine evaluate(increment)
      real(dp), intent(in) :: increment(:)
      type(return_result_t) :: state
      real(dp) :: local(8), de(4), f(8), no_history(4, 0)
      integer :: el, gp
      force = 0.0_dp
      do el = 1, nelem
        local = increment(element_dofs(mesh, el))
        associate (m => materials(mesh%element_material(el)))
        f = 0.0_dp
        do gp = 1, gauss_count
          de = matmul(b(:, :, gp, el), local)
          trial_strain(:, gp, el) = strain(:, gp, el) + de
          if (.not. m%plastic) then
            trial_stress(:, gp, el) = stress_from_strain(m%shear, m%bulk, trial_strain(:, gp, el))
            plastic(:, gp, el) = 0.0_dp
            step_backward(gp, el) = 0.0_dp
          else                                      ! the kernel's update at dt = 0 (mu = G, no history)
            trial_stress(:, gp, el) = stress(:, gp, el)
            trial_ebar(gp, el) = ebar(gp, el)
            call viscoplastic_update(m, instant(mesh%element_material(el)), m%hardening, de, trial_stress(:, gp, el), &
                                     no_history, trial_ebar(gp, el), state)
            plastic(:, gp, el) = state%plastic_increment
            step_backward(gp, el) = state%dissipation
            tangent(:, :, gp, el) = consistent_tangent(m%bulk, m%shear, state)
          end if
          f = f + weight(gp, el)*matmul(transpose(b(:, :, gp, el)), trial_stress(:, gp, el))
        end do
        end associate
        call scatter_add(mesh, el, f, force)
      end do
    end subroutine evaluate

  end subroutine solve_plastic_static

  !> The deviatoric part (s_r, s_z, s_theta, s_rz) of a stress.
  pure function deviator(sigma) result(s)
    real(dp), intent(in) :: sigma(4)
    real(dp) :: s(4)
    s = sigma
    s(1:3) = s(1:3) - sum(sigma(1:3))/3.0_dp
  end function deviator

  !> s : de for a stress (r, z, theta, rz) and an engineering-shear strain.
  pure real(dp) function contract(s, de)
    real(dp), intent(in) :: s(4), de(4)
    contract = dot_product(s, de)
  end function contract

  !> The summary keys of a plastic static solve (doc/outputs.md), energies
  !> and volumes on the energy_basis (whole body in axisymmetry);
  !> `increments` = .false. leaves out load_increments (a quasi-static run,
  !> whose increments are its time steps).
  subroutine plastic_record(settings, summary, record, increments)
    type(settings_t), intent(in) :: settings
    type(plastic_summary_t), intent(in) :: summary
    type(record_t), intent(inout) :: record
    logical, intent(in), optional :: increments
    logical :: with_increments
    with_increments = .true.
    if (present(increments)) with_increments = increments
    associate (factor => whole_body_factor(settings%geometry))
    if (with_increments) call record_put_integer(record, 'load_increments', summary%increments)
    call record_put_integer(record, 'newton_iterations', summary%iterations)
    call record_put_integer(record, 'newton_iterations_max', summary%iterations_max)
    call record_put_real(record, 'equivalent_plastic_strain_max', summary%equivalent_plastic_max)
    call record_put_real(record, 'plastic_dissipation_J', factor*summary%dissipation)
    call record_put_real(record, 'yielded_volume_m3', factor*summary%yielded_volume)
    end associate
  end subroutine plastic_record
end module visco2d_plastic_static
