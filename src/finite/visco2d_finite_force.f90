!> The internal force of the bodies at finite deformation without their
!> tangent: the lean pass that the dynamic step's equilibrium iterations
!> (modified Newton) and its sub-step ends evaluate several times a step,
!> whose neo-Hookean (NEOHOOKE, or ELASTIC as the neo-Hookean law of its G
!> and K) pointwise (no mean dilatation) elements it evaluates itself, the
!> other elements (MOONEY, HYPERFOAM, FORMULATION BBAR) through
!> visco2d_finite_solid's element_response. It computes what element_response computes for
!> the lean elements (the same formulas: b - I and J - 1 from H = du/dX, so
!> small strains keep their digits), with the reference-configuration
!> quantities (dN/dX, R, dV at the Gauss points) computed once, and neither
!> the spatial tangent nor the logarithmic strain; the strain comes from
!> the displacement gradients it keeps, when it is wanted (gradient_strains,
!> computed without the cancellation of 1 + strain: exact at small strains).
!>
!> At a Gauss point, with H the displacement gradient (in-plane block and
!> hoop H33 = u_r / R) and J = det(I + H):
!>   sigma = 2 C10 J^(-5/3) dev(b - I) + 2 (J - 1)/D1 1      (visco2d_hyperelastic, C01 = 0)
!>   f_a  += J dV (B_a^T sigma),  B_a of the current configuration (dN_a/dx = F^-T dN_a/dX, N_a/r)
!>   W    += dV (C10 (I1bar - 3) + (J - 1)^2/D1)                   (when asked for)
!> the force as dN_a/dX . P dV with the first Piola-Kirchhoff stress
!> P = J sigma F^-T, the same sum in the reference configuration.
!> test_finite_dynamic checks it against element_response to round-off.
module visco2d_finite_force
  use, intrinsic :: iso_c_binding, only: c_double
  use visco2d_kinds, only: dp, geometry_axisymmetric, formulation_bbar
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: material_t, hyperelastic_none, hyperelastic_neo_hooke, has_memory
  use visco2d_model, only: settings_t
  use visco2d_quadrilateral, only: gauss_count, gauss_xi, gauss_eta, shape_functions
  use visco2d_hyperelastic, only: hyperelastic_t, power_minus_one
  use visco2d_finite_solid, only: law_of_material
  use visco2d_finite_assembly, only: finite_memory_t, general_element
  use visco2d_assembly, only: element_dofs
  use visco2d_finite_viscoelastic, only: viscoelastic_point_t, finite_viscoelastic_t, term_count, step_shear_ratio, &
                                         internal_energy
  use visco2d_viscoelastic, only: relaxation_integral
  implicit none
  private

  public :: finite_reference_t, finite_reference_create, lean_forces, gradient_strains

  real(dp), parameter :: third = 1.0_dp/3.0_dp

  !> ln(1 + x) of the C library (C99), exact for small x: Fortran 2008 has no such intrinsic.
  interface
    pure function log1p(x) bind(c, name='log1p') result(value)
      import :: c_double
      real(c_double), value, intent(in) :: x
      real(c_double) :: value
    end function log1p
  end interface

  !> The reference configuration at the Gauss points and the constants of
  !> each element's law; `lean` false for an element that is not neo-Hookean
  !> and pointwise (element_response evaluates it).
  type :: finite_reference_t
    logical, allocatable :: lean(:)                  !< per element
    logical, allocatable :: relaxes(:)               !< per element: lean, and its material relaxes (Simo)
    logical :: axisymmetric = .true.
    real(dp) :: shape(4, gauss_count) = 0.0_dp       !< N_a at the Gauss points
    real(dp), allocatable :: gradients(:, :, :, :)   !< dN_a/dX_j (j, a, gauss, element)
    real(dp), allocatable :: radius(:, :)            !< R at the point (gauss, element; 1 in plane strain)
    real(dp), allocatable :: volume(:, :)            !< dV = det(dX/dxi) R (gauss, element)
    real(dp), allocatable :: c10(:), d1(:)           !< the element's neo-Hookean constants
    real(dp), allocatable :: bulk2(:)                !< 2 / D1 (= K), per element
    real(dp), allocatable :: inverse_radius(:, :)    !< 1 / R at the point (gauss, element)
  end type finite_reference_t

contains

  !> The reference quantities of the mesh, and which elements the lean pass
  !> evaluates. An element degenerate in the undeformed mesh is left to
  !> element_response (which reports it).
  pure function finite_reference_create(mesh, materials, settings) result(reference)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    type(finite_reference_t) :: reference
    type(hyperelastic_t) :: law
    real(dp) :: n(4), dn(2, 4), xy(2, 4), jacobian(2, 2), det, inverse(2, 2)
    integer :: e, g
    reference%axisymmetric = settings%geometry == geometry_axisymmetric
    allocate(reference%lean(mesh%nelem), reference%relaxes(mesh%nelem))
    reference%lean = settings%formulation /= formulation_bbar
    allocate(reference%gradients(2, 4, gauss_count, mesh%nelem), reference%radius(gauss_count, mesh%nelem), &
             reference%volume(gauss_count, mesh%nelem), reference%c10(mesh%nelem), reference%d1(mesh%nelem))
    do g = 1, gauss_count
      call shape_functions(gauss_xi(g), gauss_eta(g), n, dn)
      reference%shape(:, g) = n
    end do
    do e = 1, mesh%nelem
      associate (material => materials(mesh%element_material(e)))
      if (material%hyperelastic /= hyperelastic_none .and. material%hyperelastic /= hyperelastic_neo_hooke) &
        reference%lean(e) = .false.
      reference%relaxes(e) = has_memory(material)     ! Simo's viscoelasticity on the neo-Hookean law of G0 and K
      law = law_of_material(material)
      if (law%c01 /= 0.0_dp) reference%lean(e) = .false.
      reference%c10(e) = law%c10
      reference%d1(e) = law%d1
      end associate
      xy = mesh%xy(:, mesh%connectivity(:, e))
      do g = 1, gauss_count
        call shape_functions(gauss_xi(g), gauss_eta(g), n, dn)
        jacobian = matmul(dn, transpose(xy))                ! (i, j) = d X_j / d xi_i
        det = jacobian(1, 1)*jacobian(2, 2) - jacobian(1, 2)*jacobian(2, 1)
        if (.not. (det > 0.0_dp)) then
          reference%lean(e) = .false.
          det = 1.0_dp
        end if
        inverse = reshape([jacobian(2, 2), -jacobian(2, 1), -jacobian(1, 2), jacobian(1, 1)], [2, 2])/det
        reference%gradients(:, :, g, e) = matmul(inverse, dn)
        if (reference%axisymmetric) then
          reference%radius(g, e) = dot_product(n, xy(1, :))
          if (.not. (reference%radius(g, e) > 0.0_dp)) reference%lean(e) = .false.
        else
          reference%radius(g, e) = 1.0_dp
        end if
        reference%volume(g, e) = det*reference%radius(g, e)
      end do
    end do
    reference%bulk2 = 2.0_dp/reference%d1
    reference%inverse_radius = 1.0_dp/reference%radius
    reference%relaxes = reference%relaxes .and. reference%lean
  end function finite_reference_create

  !> f(U), the Cauchy stresses (rr, zz, tt, rz) and W (J, per radian in
  !> axisymmetry) at the displacement U (equation order), and for
  !> gradient_strains the displacement gradients (H11, H21, H12, H22, H33)
  !> at the Gauss points of the lean elements and the logarithmic strains of
  !> the others. `inverted`: the first element inverted or through the axis
  !> at U (0: none), and then the outputs are incomplete.
  pure subroutine lean_forces(reference, mesh, materials, settings, displacement, force, stress, energy, inverted, &
                              gradient, strain, memory, history, next)
    type(finite_reference_t), intent(in) :: reference
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    real(dp), intent(in) :: displacement(:)
    real(dp), intent(out) :: force(:), stress(:, :, :)
    real(dp), intent(out), optional :: energy        !< W; absent: not computed (an iteration's force)
    integer, intent(out) :: inverted
    real(dp), intent(inout) :: gradient(:, :, :), strain(:, :, :)
    type(finite_memory_t), intent(in), optional :: memory           !< materials with memory (general_element)
    type(viscoelastic_point_t), intent(in), optional :: history(:, :)
    type(viscoelastic_point_t), intent(inout), optional :: next(:, :)
    real(dp) :: element_force(8), element_stiffness(8, 8), element_energy
    integer :: dofs(8)
    logical :: valid
    real(dp) :: u(2, 4), f(2, 4), h11, h12, h21, h22, h33, in_plane, change, jacobian, scale, trace, mean
    real(dp) :: d11, d22, d33, d12, s11, s22, s33, s12, factor, pressure, k, p11, p12, p21, p22, hoop
    real(dp) :: exponent_minus_one, root, work, iso0(4), iso(4), long_term, energy_density
    real(dp), allocatable :: decay(:, :), integral(:, :), mu_hat(:)
    integer :: e, g, a, node, m
    logical :: want_energy
    inverted = 0
    force = 0.0_dp
    work = 0.0_dp
    want_energy = present(energy)
    if (present(memory)) call step_factors(memory, decay, integral, mu_hat)
    do e = 1, mesh%nelem
      if (.not. reference%lean(e)) then
        dofs = element_dofs(mesh, e)
        if (present(memory) .and. present(history) .and. present(next)) then   ! (finite_assemble's note)
          call general_element(mesh, materials, settings, e, displacement, .false., element_force, element_stiffness, &
                               stress(:, :, e), strain(:, :, e), element_energy, valid, memory, history, next)
        else
          call general_element(mesh, materials, settings, e, displacement, .false., element_force, element_stiffness, &
                               stress(:, :, e), strain(:, :, e), element_energy, valid)
        end if
        if (.not. valid) then
          inverted = e
          return
        end if
        force(dofs) = force(dofs) + element_force
        work = work + element_energy
        cycle
      end if
      do a = 1, 4
        node = 2*mesh%equation(mesh%connectivity(a, e))        ! the node's z equation (band order)
        u(:, a) = displacement(node - 1:node)
      end do
      f = 0.0_dp
      do g = 1, gauss_count
        associate (gradients => reference%gradients(:, :, g, e))
        h11 = u(1, 1)*gradients(1, 1) + u(1, 2)*gradients(1, 2) + u(1, 3)*gradients(1, 3) + u(1, 4)*gradients(1, 4)
        h12 = u(1, 1)*gradients(2, 1) + u(1, 2)*gradients(2, 2) + u(1, 3)*gradients(2, 3) + u(1, 4)*gradients(2, 4)
        h21 = u(2, 1)*gradients(1, 1) + u(2, 2)*gradients(1, 2) + u(2, 3)*gradients(1, 3) + u(2, 4)*gradients(1, 4)
        h22 = u(2, 1)*gradients(2, 1) + u(2, 2)*gradients(2, 2) + u(2, 3)*gradients(2, 3) + u(2, 4)*gradients(2, 4)
        h33 = 0.0_dp
        if (reference%axisymmetric) h33 = dot_product(reference%shape(:, g), u(1, :))*reference%inverse_radius(g, e)
        in_plane = h11 + h22 + h11*h22 - h12*h21              ! det(I + H_2x2) - 1
        if (.not. (1.0_dp + in_plane > 0.0_dp .and. 1.0_dp + h33 > 0.0_dp)) then
          inverted = e
          return
        end if
        change = h33 + in_plane*(1.0_dp + h33)                 ! J - 1 (visco2d_hyperelastic's volume_change)
        jacobian = 1.0_dp + change
        root = inverse_cube_root(jacobian)
        scale = root*root                                      ! J^(-2/3)
        d11 = 2.0_dp*h11 + h11*h11 + h12*h12                  ! b - I = H + H^T + H H^T
        d22 = 2.0_dp*h22 + h21*h21 + h22*h22
        d12 = h12 + h21 + h11*h21 + h12*h22
        d33 = 2.0_dp*h33 + h33*h33
        mean = (d11 + d22 + d33)*third
        factor = 2.0_dp*reference%c10(e)*scale*(root*scale)   ! 2 C10 J^(-5/3), J^-1 = root^3: no division
        pressure = change*reference%bulk2(e)                  ! 2 (J - 1)/D1
        iso0 = factor*[d11 - mean, d22 - mean, d33 - mean, d12]   ! the isochoric part
        iso = iso0
        long_term = 1.0_dp
        if (reference%relaxes(e)) then                         ! Simo: mu_hat sigma0_iso + F H_n F^T / J
          m = mesh%element_material(e)
          long_term = memory%laws(m)%long_term_ratio
          iso = relaxed_stress(memory%laws(m), decay(:, m), integral(:, m), mu_hat(m), history(g, e), &
                               [h11, h21, h12, h22, h33], jacobian, iso0)
          if (present(next)) call next_history(memory%laws(m), decay(:, m), integral(:, m), history(g, e), &
                                               [h11, h21, h12, h22, h33], jacobian, iso0, next(g, e))
        end if
        s11 = iso(1) + pressure
        s22 = iso(2) + pressure
        s33 = iso(3) + pressure
        s12 = iso(4)
        stress(:, g, e) = [s11, s22, s33, s12]
        if (want_energy) then
          if (abs(change) >= 1.0e-3_dp) then                   ! power_minus_one's own branch, without a second power
            exponent_minus_one = scale - 1.0_dp
          else
            exponent_minus_one = power_minus_one(change, -2.0_dp/3.0_dp)
          end if
          trace = scale*(d11 + d22 + d33) + 3.0_dp*exponent_minus_one               ! I1bar - 3
          energy_density = long_term*reference%c10(e)*trace + change**2/reference%d1(e)
          if (reference%relaxes(e) .and. present(next)) energy_density = energy_density + &
            internal_energy(memory%laws(m), next(g, e))
          work = work + reference%volume(g, e)*energy_density
        end if
        gradient(:, g, e) = [h11, h21, h12, h22, h33]
        ! B_a^T sigma dv with dN_a/dx = F^-T dN_a/dX is dN_a/dX . P dV, P = J sigma F^-T (the first
        ! Piola-Kirchhoff stress): in the plane J/det(F_2x2) = 1 + H33, F^-T det(F_2x2) = the cofactors,
        ! and the hoop term N_a sigma_tt dv / r = N_a sigma_tt det(F_2x2) dV / R.
        k = (1.0_dp + h33)*reference%volume(g, e)
        p11 = k*(s11*(1.0_dp + h22) - s12*h12)
        p12 = k*(s12*(1.0_dp + h11) - s11*h21)
        p21 = k*(s12*(1.0_dp + h22) - s22*h12)
        p22 = k*(s22*(1.0_dp + h11) - s12*h21)
        hoop = 0.0_dp
        if (reference%axisymmetric) hoop = (1.0_dp + in_plane)*reference%volume(g, e)*s33*reference%inverse_radius(g, e)
        do a = 1, 4
          f(1, a) = f(1, a) + gradients(1, a)*p11 + gradients(2, a)*p12 + hoop*reference%shape(a, g)
          f(2, a) = f(2, a) + gradients(1, a)*p21 + gradients(2, a)*p22
        end do
        end associate
      end do
      do a = 1, 4
        node = 2*mesh%equation(mesh%connectivity(a, e))
        force(node - 1:node) = force(node - 1:node) + f(:, a)
      end do
    end do
    if (want_energy) energy = work
  end subroutine lean_forces

  !> Per material with memory, over memory%dt: exp(-beta_i dt), J(beta_i dt)
  !> (eq. [22]) and mu_hat = gamma_inf + sum gamma_i J(beta_i dt).
  pure subroutine step_factors(memory, decay, integral, mu_hat)
    type(finite_memory_t), intent(in) :: memory
    real(dp), allocatable, intent(out) :: decay(:, :), integral(:, :), mu_hat(:)
    integer :: m, i, terms
    terms = 0
    do m = 1, size(memory%relaxes)
      if (memory%relaxes(m)) terms = max(terms, term_count(memory%laws(m)))
    end do
    allocate(decay(terms, size(memory%relaxes)), integral(terms, size(memory%relaxes)), mu_hat(size(memory%relaxes)))
    decay = 0.0_dp
    integral = 0.0_dp
    mu_hat = 1.0_dp
    do m = 1, size(memory%relaxes)
      if (.not. memory%relaxes(m)) cycle
      associate (law => memory%laws(m))
      mu_hat(m) = step_shear_ratio(law, memory%dt)
      do i = 1, term_count(law)
        decay(i, m) = exp(-law%rate(i)*memory%dt)
        integral(i, m) = relaxation_integral(law%rate(i)*memory%dt)
      end do
      end associate
    end do
  end subroutine step_factors

  !> F A F^T / J of a symmetric A (Voigt rr, zz, tt, rz) for F = I + H, H given as (H11, H21, H12, H22, H33).
  pure function push_forward(h, a, jacobian) result(b)
    real(dp), intent(in) :: h(5), a(4), jacobian
    real(dp) :: b(4), f11, f21, f12, f22
    f11 = 1.0_dp + h(1)
    f21 = h(2)
    f12 = h(3)
    f22 = 1.0_dp + h(4)
    b(1) = f11*(f11*a(1) + f12*a(4)) + f12*(f11*a(4) + f12*a(2))
    b(2) = f21*(f21*a(1) + f22*a(4)) + f22*(f21*a(4) + f22*a(2))
    b(4) = f11*(f21*a(1) + f22*a(4)) + f12*(f21*a(4) + f22*a(2))
    b(3) = (1.0_dp + h(5))**2*a(3)
    b = b/jacobian
  end function push_forward

  !> The isochoric Cauchy stress of Simo's law over the step (visco2d_finite_viscoelastic):
  !> mu_hat sigma0_iso + F H_n F^T / J, H_n = sum_i (exp(-x_i) Q_i - gamma_i J(x_i) S0_n).
  pure function relaxed_stress(law, decay, integral, mu_hat, point, h, jacobian, iso0) result(iso)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: decay(:), integral(:), mu_hat, h(5), jacobian, iso0(4)
    type(viscoelastic_point_t), intent(in) :: point
    real(dp) :: iso(4), held(4)
    integer :: i
    held = 0.0_dp
    do i = 1, term_count(law)
      held = held + decay(i)*point%internal(:, i) - law%ratio(i)*integral(i)*point%instantaneous
    end do
    iso = mu_hat*iso0
    if (term_count(law) > 0) iso = iso + push_forward(h, held, jacobian)
  end function relaxed_stress

  !> The history at the step's end: S0 = F^-1 (J sigma0_iso) F^-T and
  !> Q_i = exp(-x_i) Q_i,n + gamma_i J(x_i) (S0 - S0_n).
  pure subroutine next_history(law, decay, integral, point, h, jacobian, iso0, next)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: decay(:), integral(:), h(5), jacobian, iso0(4)
    type(viscoelastic_point_t), intent(in) :: point
    type(viscoelastic_point_t), intent(inout) :: next
    real(dp) :: inverse(5), det, s0(4)
    integer :: i
    det = (1.0_dp + h(1))*(1.0_dp + h(4)) - h(2)*h(3)
    ! F^-1 = [[1 + H22, -H12], [-H21, 1 + H11]] / det in the plane, 1 / (1 + H33) in the hoop, as I + H':
    inverse = [(1.0_dp + h(4))/det - 1.0_dp, -h(2)/det, -h(3)/det, (1.0_dp + h(1))/det - 1.0_dp, &
               1.0_dp/(1.0_dp + h(5)) - 1.0_dp]
    s0 = push_forward(inverse, jacobian*iso0, 1.0_dp)
    if (allocated(next%internal)) then
      if (size(next%internal, 2) /= term_count(law)) deallocate(next%internal)
    end if
    if (.not. allocated(next%internal)) allocate(next%internal(4, term_count(law)))
    next%instantaneous = s0
    do i = 1, term_count(law)
      next%internal(:, i) = decay(i)*point%internal(:, i) + law%ratio(i)*integral(i)*(s0 - point%instantaneous)
    end do
  end subroutine next_history

  !> x^(-1/3) for x > 0: from the cubic Taylor polynomial in c = x - 1,
  !> y = 1 - c/3 + 2 c^2/9 - 14 c^3/81, the update y (1 + r/3 + 2 r^2/9),
  !> r = 1 - x y^3 (the series of y (1 - r)^(-1/3), cubically convergent; |r|
  !> is below 0.05 from the start for 0.5 < x < 1.6, the volume ratios of
  !> flesh, and below 1e-5 for |x - 1| < 0.09, where one update reaches
  !> round-off), several times cheaper
  !> than the library's power or cube root; outside that range the power.
  pure real(dp) function inverse_cube_root(x) result(y)
    real(dp), intent(in) :: x
    real(dp) :: r, c
    integer :: k
    if (.not. (x > 0.5_dp .and. x < 1.6_dp)) then
      y = x**(-1.0_dp/3.0_dp)
      return
    end if
    c = x - 1.0_dp
    y = 1.0_dp - c*(1.0_dp/3.0_dp - c*(2.0_dp/9.0_dp - c*(14.0_dp/81.0_dp)))
    do k = 1, 6
      r = 1.0_dp - x*y*y*y
      y = y*(1.0_dp + r*(1.0_dp/3.0_dp + r*(2.0_dp/9.0_dp)))
      if (abs(r) < 1.0e-5_dp) exit                    ! the update's error, 14/81 r^3, below 2e-16: one update for |x - 1| < 0.09
    end do
  end function inverse_cube_root

  !> The logarithmic strains ln V (rr, zz, tt, engineering rz) of the
  !> gradients lean_forces kept, from b - I = H + H^T + H H^T without
  !> cancellation: the in-plane eigenvalues 1 + x_1,2 of b (x = m +- rho,
  !> m = tr(b - I)/2 over the pair, rho the radius), ln V = h_2 I + (h_1 - h_2) P_1
  !> with h_k = ln(1 + x_k)/2 and the projector P_1 = (b - I - x_2 I)/(2 rho), the
  !> factor (h_1 - h_2)/(2 rho) taken as ln(1 + y)/(2 y (1 + x_2)), y = 2 rho/(1 + x_2),
  !> which stays exact as rho -> 0; the hoop strain ln(1 + H33).
  pure subroutine gradient_strains(reference, gradient, strain)
    type(finite_reference_t), intent(in) :: reference
    real(dp), intent(in) :: gradient(:, :, :)
    real(dp), intent(inout) :: strain(:, :, :)       !< set at the lean elements, kept at the others
    real(dp) :: d11, d22, d12, m, rho, x2, y, ratio, h2
    integer :: e, g
    do e = 1, size(gradient, 3)
      if (.not. reference%lean(e)) cycle
      do g = 1, size(gradient, 2)
        associate (h => gradient(:, g, e))             ! H11, H21, H12, H22, H33
        d11 = 2.0_dp*h(1) + h(1)*h(1) + h(3)*h(3)
        d22 = 2.0_dp*h(4) + h(2)*h(2) + h(4)*h(4)
        d12 = h(3) + h(2) + h(1)*h(2) + h(3)*h(4)
        m = 0.5_dp*(d11 + d22)
        rho = hypot(0.5_dp*(d11 - d22), d12)
        x2 = m - rho
        y = 2.0_dp*rho/(1.0_dp + x2)
        if (y > 1.0e-8_dp) then
          ratio = 0.5_dp*log1p(y)/(y*(1.0_dp + x2))
        else                                           ! ln(1 + y)/y = 1 - y/2 + O(y^2)
          ratio = 0.5_dp*(1.0_dp - 0.5_dp*y)/(1.0_dp + x2)
        end if
        h2 = 0.5_dp*log1p(x2)
        strain(1, g, e) = h2 + ratio*(d11 - x2)
        strain(2, g, e) = h2 + ratio*(d22 - x2)
        strain(3, g, e) = log1p(h(5))
        strain(4, g, e) = 2.0_dp*ratio*d12
        end associate
      end do
    end do
  end subroutine gradient_strains
end module visco2d_finite_force
