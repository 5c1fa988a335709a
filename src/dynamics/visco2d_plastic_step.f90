!> The constitutive pass of a time step with a PLASTIC material: the pass of
!> visco2d_operators (strain increments B du, eq. [4]; stresses; internal
!> forces) with the Gauss points of plastic materials returned to the
!> yield surface (visco2d_plasticity, radial return with the step's shear
!> modulus mu_n in series with the Prony law, eqs. [13], [14], [21]-[23]).
!> Elastic materials get exactly operators_trial_stress's stresses.
!>
!> At a plastic Gauss point over an interval (the solve interval h or the
!> sub-step) the deviatoric trial stress is
!>   s_trial = dev(sigma_n) + 2 mu_n dev(de) + s0        (eqs. [13], [21], [23])
!> s0 the history stress of the interval (precomputed, as for the elastic
!> pass), the mean stress p_n + K tr(de) (eq. [14]), and
!> s = radial_return(s_trial). The plastic strain increment de_p goes back to
!> the caller, which updates the Prony histories with de - de_p (eq. [24]):
!> the springs and dashpots see only the strain the slider did not take.
module visco2d_plastic_step
  use visco2d_kinds, only: dp, geometry_axisymmetric
  use visco2d_error, only: error_t, set_error
  use visco2d_deck, only: deck_t
  use visco2d_material, only: material_t, elastic_matrix
  use visco2d_strings, only: integer_text
  use visco2d_element, only: gauss_count
  use visco2d_banded, only: band_matrix_t, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_of_card, solve_failure_text
  use visco2d_assembly, only: assemble_stiffness, node_dof, element_dofs
  use visco2d_pad_mesh, only: body_nodes
  use visco2d_operators, only: operators_t, operators_element_force
  use visco2d_plasticity, only: return_result_t, radial_return, yield_stress, consistent_tangent
  implicit none
  private

  public :: plastic_trial_stress, plastic_work, yield_limits, residual_flattening, plastic_point_tangents

contains

  !> The elastic limit of every Gauss point at the equivalent plastic strain
  !> ebar: (2/3) sigma_y(ebar)^2, the largest |s|^2 an elastic step may reach
  !> (von Mises: |s| <= sqrt(2/3) sigma_y); -1 at the points of materials
  !> without plasticity. Computed when ebar changes, so the pass compares;
  !> with `previous` (the ebar `limit` holds), only at the points whose ebar
  !> changed.
  pure subroutine yield_limits(materials, element_material, ebar, limit, previous)
    type(material_t), intent(in) :: materials(:)
    integer, intent(in) :: element_material(:)
    real(dp), intent(in) :: ebar(:, :)
    real(dp), intent(inout) :: limit(:, :)
    real(dp), intent(in), optional :: previous(:, :)
    integer :: e, g
    do e = 1, size(element_material)
      associate (material => materials(element_material(e)))
      do g = 1, gauss_count
        if (present(previous)) then
          if (previous(g, e) == ebar(g, e)) cycle
        end if
        if (material%plastic) then
          limit(g, e) = 2.0_dp/3.0_dp*yield_stress(material%hardening, ebar(g, e))**2
        else
          limit(g, e) = -1.0_dp
        end if
      end do
      end associate
    end do
  end subroutine yield_limits

  !> The pass over the elements for the increment du: strain increments,
  !> stresses (returned where a plastic material yields: `limit` from
  !> yield_limits at the interval's start), internal forces; for each Gauss
  !> point ebar after the interval (from `ebar`, at its start) and the
  !> plastic strain increment de_p (engineering shear). `yielded`: the
  !> number of Gauss points that yielded in the interval. One sweep over the
  !> elements, as operators_trial_stress: the trial stress of point_return
  !> is inlined and radial_return called only outside the yield surface,
  !> since this pass runs at every equilibrium iteration and most points
  !> stay elastic.
  pure subroutine plastic_trial_stress(operators, materials, element_material, limit, du, shear, bulk, stress, ebar, &
                                       increments, trial, force, ebar_next, plastic_increments, yielded, history)
    type(operators_t), intent(in) :: operators
    type(material_t), intent(in) :: materials(:)
    integer, intent(in) :: element_material(:)
    real(dp), intent(in) :: limit(:, :)                       !< (gauss_count, nelem) yield_limits
    real(dp), intent(in) :: du(:)
    real(dp), intent(in) :: shear(:), bulk(:)                 !< (nelem) moduli over the interval
    real(dp), intent(in) :: stress(:, :, :)                   !< (4, gauss_count, nelem) at its start
    real(dp), intent(in) :: ebar(:, :)                        !< (gauss_count, nelem) at its start
    real(dp), intent(out) :: increments(:, :, :), trial(:, :, :)
    real(dp), intent(out) :: force(:)
    real(dp), intent(out) :: ebar_next(:, :), plastic_increments(:, :, :)
    integer, intent(out) :: yielded
    real(dp), intent(in), optional :: history(:, :, :)       !< (4, gauss_count, nelem) s0 of the interval
    type(return_result_t) :: state
    real(dp) :: local(8), increment(4), sigma(4), s0(4), mean, volumetric, element_force(8)
    real(dp) :: element_stress(4, gauss_count)      ! contiguous: no packed copy of trial(:, :, e) for the force
    integer :: e, g, j
    force = 0.0_dp
    yielded = 0
    s0 = 0.0_dp
    plastic_increments = 0.0_dp                     ! set below at the points that yield
    ebar_next = ebar
    do e = 1, operators%nelem
      do j = 1, 8
        local(j) = du(operators%dofs(j, e))
      end do
      do g = 1, gauss_count
        increment = operators%b(:, 1, g, e)*local(1)   ! B du (eq. [4]); from the first term: no zeroing call
        do j = 2, 8
          increment = increment + operators%b(:, j, g, e)*local(j)
        end do
        if (present(history)) s0 = history(:, g, e)
        volumetric = increment(1) + increment(2) + increment(3)
        if (limit(g, e) < 0.0_dp) then              ! no plasticity: as operators_trial_stress, eqs. [13], [14]
          sigma(1:3) = stress(1:3, g, e) + bulk(e)*volumetric + 2.0_dp*shear(e)*(increment(1:3) - volumetric/3.0_dp)
          sigma(4) = stress(4, g, e) + shear(e)*increment(4)
          sigma = sigma + s0
        else                                        ! point_return: the deviatoric trial of eqs. [13], [21], [23]
          mean = sum(stress(1:3, g, e))/3.0_dp
          sigma(1:3) = stress(1:3, g, e) - mean + 2.0_dp*shear(e)*(increment(1:3) - volumetric/3.0_dp)
          sigma(4) = stress(4, g, e) + shear(e)*increment(4)
          sigma = sigma + s0
          if (sigma(1)**2 + sigma(2)**2 + sigma(3)**2 + 2.0_dp*sigma(4)**2 > limit(g, e)) then
            state = radial_return(materials(element_material(e))%hardening, shear(e), sigma, ebar(g, e))
            sigma = state%stress
            if (state%yielded) then
              yielded = yielded + 1
              plastic_increments(:, g, e) = state%plastic_increment
              ebar_next(g, e) = state%equivalent_plastic
            end if
          end if
          sigma(1:3) = sigma(1:3) + mean + bulk(e)*volumetric     ! the mean stress p_n + K tr(de), eq. [14]
        end if
        increments(:, g, e) = increment
        element_stress(:, g) = sigma
      end do
      trial(:, :, e) = element_stress
      element_force = operators_element_force(operators, e, element_stress)
      do j = 1, 8
        force(operators%dofs(j, e)) = force(operators%dofs(j, e)) + element_force(j)
      end do
    end do
  end subroutine plastic_trial_stress

  !> The consistent tangents over the interval at the increment du
  !> (ANALYSIS DYNAMIC NEWTON=FULL): for each Gauss point C =
  !> consistent_tangent of its return over the interval from its start
  !> (Simo and Hughes Box 3.2, with the interval's mu and K: the trial of
  !> plastic_trial_stress), the elastic matrix where the point stays inside
  !> the yield surface or its material has no plasticity; into `tangent`
  !> (4, 4, gauss_count, nelem), for assemble_point_tangents.
  pure subroutine plastic_point_tangents(operators, materials, element_material, limit, du, shear, bulk, stress, ebar, &
                                         tangent, history)
    type(operators_t), intent(in) :: operators
    type(material_t), intent(in) :: materials(:)
    integer, intent(in) :: element_material(:)
    real(dp), intent(in) :: limit(:, :), du(:), shear(:), bulk(:), stress(:, :, :), ebar(:, :)
    real(dp), intent(out) :: tangent(:, :, :, :)
    real(dp), intent(in), optional :: history(:, :, :)
    type(return_result_t) :: state
    real(dp) :: local(8), increment(4), sigma(4), s0(4), mean, volumetric
    integer :: e, g, j
    s0 = 0.0_dp
    do e = 1, operators%nelem
      do j = 1, 8
        local(j) = du(operators%dofs(j, e))
      end do
      do g = 1, gauss_count
        tangent(:, :, g, e) = elastic_matrix(shear(e), bulk(e))
        if (limit(g, e) < 0.0_dp) cycle             ! no plasticity
        increment = matmul(operators%b(:, :, g, e), local)     ! plastic_trial_stress's trial (eqs. [13], [21], [23])
        if (present(history)) s0 = history(:, g, e)
        volumetric = increment(1) + increment(2) + increment(3)
        mean = sum(stress(1:3, g, e))/3.0_dp
        sigma(1:3) = stress(1:3, g, e) - mean + 2.0_dp*shear(e)*(increment(1:3) - volumetric/3.0_dp)
        sigma(4) = stress(4, g, e) + shear(e)*increment(4)
        sigma = sigma + s0
        if (sigma(1)**2 + sigma(2)**2 + sigma(3)**2 + 2.0_dp*sigma(4)**2 <= limit(g, e)) cycle
        state = radial_return(materials(element_material(e))%hardening, shear(e), sigma, ebar(g, e))
        if (state%yielded) tangent(:, :, g, e) = consistent_tangent(bulk(e), shear(e), state)
      end do
    end do
  end subroutine plastic_point_tangents

  !> The plastic work of an interval, sum over the Gauss points of
  !> 1/2 (s_start + s_end) : de_p |J| r (the trapezoid, as the energy books
  !> take the internal force's work; per radian in axisymmetry), J.
  pure real(dp) function plastic_work(operators, stress_start, stress_end, plastic_increments) result(work)
    type(operators_t), intent(in) :: operators
    real(dp), intent(in) :: stress_start(:, :, :), stress_end(:, :, :), plastic_increments(:, :, :)
    real(dp) :: s(4)
    integer :: e, g
    work = 0.0_dp
    do e = 1, operators%nelem
      do g = 1, gauss_count
        if (all(plastic_increments(:, g, e) == 0.0_dp)) cycle
        s = 0.5_dp*(stress_start(:, g, e) + stress_end(:, g, e))
        s(1:3) = s(1:3) - sum(s(1:3))/3.0_dp
        work = work + operators%weight(g, e)*dot_product(s, plastic_increments(:, g, e))
      end do
    end do
  end function plastic_work

  !> The permanent shortening of an axisymmetric body along its axis that its
  !> plastic strain leaves once unloaded, m: the displacement u of the body
  !> with the plastic strain as an eigenstrain, S u = sum B^T D eps_p |J| r
  !> (the instantaneous elastic moduli G, K; the axis free in z but for the
  !> far pole, u_r = 0 on the axis), and the shortening
  !> u_z(contact pole) - u_z(far pole), the poles the body's lowest and
  !> highest nodes on the axis (a PAD's nodes held: the body alone). A
  !> homogeneous plastic strain gives it exactly
  !> (-eps_p,z times the height); `found` is false for plane strain or a body
  !> without a node of the axis at both poles.
  subroutine residual_flattening(deck, b, weight, plastic_strain, shortening, found, error)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: b(:, :, :, :), weight(:, :)      !< B (4, 8, gauss, nelem) and |J| r (gauss, nelem)
    real(dp), intent(in) :: plastic_strain(:, :, :)          !< (4, gauss_count, nelem)
    real(dp), intent(out) :: shortening
    logical, intent(out) :: found
    type(error_t), allocatable, intent(inout) :: error
    type(band_matrix_t) :: stiffness
    type(factor_t) :: factor
    real(dp), allocatable :: shear(:), bulk(:), load(:), zeros(:)
    logical, allocatable :: supports(:)
    real(dp) :: d(4, 4), element_force(8)
    integer :: e, g, node, bottom, top, info, status, dofs(8)
    associate (mesh => deck%mesh)
    shortening = 0.0_dp
    found = .false.
    if (deck%settings%geometry /= geometry_axisymmetric) return
    bottom = 0
    top = 0
    allocate(supports(2*mesh%nnode), load(2*mesh%nnode), zeros(2*mesh%nnode))
    supports = .false.
    load = 0.0_dp
    zeros = 0.0_dp
    do node = 1, body_nodes(deck)
      if (mesh%xy(1, node) /= 0.0_dp) cycle
      supports(node_dof(mesh, node, 1)) = .true.
      if (bottom == 0) bottom = node
      if (top == 0) top = node
      if (mesh%xy(2, node) < mesh%xy(2, bottom)) bottom = node
      if (mesh%xy(2, node) > mesh%xy(2, top)) top = node
    end do
    if (bottom == 0 .or. top == bottom) return
    supports(node_dof(mesh, top, 2)) = .true.
    do node = body_nodes(deck) + 1, mesh%nnode        ! a PAD's nodes: held, the body is unloaded alone
      supports(node_dof(mesh, node, 1)) = .true.
      supports(node_dof(mesh, node, 2)) = .true.
    end do
    shear = deck%materials(mesh%element_material)%shear
    bulk = deck%materials(mesh%element_material)%bulk
    call assemble_stiffness(mesh, deck%settings, shear, bulk, stiffness)
    do e = 1, mesh%nelem
      if (all(plastic_strain(:, :, e) == 0.0_dp)) cycle
      d = elastic_matrix(shear(e), bulk(e))
      element_force = 0.0_dp
      do g = 1, gauss_count
        element_force = element_force + weight(g, e)*matmul(transpose(b(:, :, g, e)), matmul(d, plastic_strain(:, g, e)))
      end do
      dofs = element_dofs(mesh, e)
      load(dofs) = load(dofs) + element_force
    end do
    call factor_compute(factor, stiffness, supports, info, solver_of_card(deck%settings%solver))
    if (info /= 0) then
      call set_error(error, 'the elastic stiffness of the unloaded body is singular at equation '// &
        integer_text(info)//' (the residual deformation of the plastic strain)')
      return
    end if
    call band_constrain_rhs(stiffness, supports, zeros, load)
    call factor_solve(factor, load, status)
    if (status /= 0) then
      call set_error(error, solve_failure_text(status))
      return
    end if
    shortening = load(node_dof(mesh, bottom, 2)) - load(node_dof(mesh, top, 2))
    found = .true.
    end associate
  end subroutine residual_flattening

end module visco2d_plastic_step
