!> Finite deformation (src/finite/): the hyperelastic laws and the
!> current-configuration element, against closed forms and differences.
!>  1. Small-strain limit: at F = I + eps H the neo-Hookean and Mooney-Rivlin
!>     stress is Hooke's law with G = 2 (C10 + C01), K = 2 / D1 and the
!>     tangent its elasticity matrix (to O(eps)).
!>  2. Stress from the energy: tau : H = dW/ds of F(s) = (1 + s H) F (the
!>     Kirchhoff stress power per reference volume), central differences.
!>  3. Tangent from the stress: J c : H = d tau/ds - H tau - tau H^T (the
!>     Oldroyd rate of tau for the velocity gradient H, symmetric), central
!>     differences at random F (in-plane rotation, stretches to 0.2).
!>  4. Uniaxial stress to 80 % compression: the lateral stretch solved from
!>     sigma_rr = 0 by bisection on the closed-form pressure balance, then
!>     sigma_zz against 2 C10 J^(-5/3) (lambda^2 - lambda_t^2); the nearly
!>     incompressible limit against 2 C10 (lambda^2 - 1/lambda).
!>  5. Objectivity: sigma(Q F) = Q sigma(F) Q^T.
!>  6. The element: its tangent against central differences of its force
!>     (axisymmetric and plane strain, pointwise and mean dilatation, at a
!>     distorted element under a large general displacement); a homogeneous
!>     deformation reproduced exactly (the patch: every Gauss point's F
!>     equal to the prescribed one, the force that of the boundary
!>     tractions); a rigid rotation in plane strain leaves no stress.
program test_finite
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_plane_strain, formulation_standard, formulation_bbar
  use visco2d_hyperelastic, only: hyperelastic_t, isochoric_response, hyperelastic_response, volumetric_response, &
                                  identity3
  use visco2d_material, only: material_t, elastic_matrix, hyperelastic_neo_hooke, hyperelastic_mooney_rivlin
  use visco2d_finite_element, only: finite_point_t, finite_kinematics
  use visco2d_finite_solid, only: element_response, logarithmic_strain
  use visco2d_testing, only: check, check_close, test_summary
  implicit none

  type(hyperelastic_t) :: neo, mooney
  real(dp) :: shear, bulk

  shear = 1.2e6_dp
  bulk = 5.0e6_dp
  neo = hyperelastic_t(c10=0.5_dp*shear, c01=0.0_dp, d1=2.0_dp/bulk)
  mooney = hyperelastic_t(c10=0.35_dp*shear, c01=0.15_dp*shear, d1=2.0_dp/bulk)

  call small_strain_limit(neo, 'neo-Hookean')
  call small_strain_limit(mooney, 'Mooney-Rivlin')
  call stress_from_energy(neo, 'neo-Hookean')
  call stress_from_energy(mooney, 'Mooney-Rivlin')
  call tangent_from_stress(neo, 'neo-Hookean')
  call tangent_from_stress(mooney, 'Mooney-Rivlin')
  call uniaxial_compression()
  call objectivity()
  call element_tangent()
  call patch_test()
  call rigid_rotation()
  call test_summary('test_finite')

contains

  !> F = I + eps H: sigma = D eps_v (Hooke) to O(eps^2), c = D to O(eps).
  subroutine small_strain_limit(law, name)
    type(hyperelastic_t), intent(in) :: law
    character(*), intent(in) :: name
    real(dp), parameter :: eps = 1.0e-7_dp
    real(dp) :: h(3, 3), f(3, 3), stress(4), tangent(4, 4), d(4, 4), strain(4)
    h = 0.0_dp
    h(1, 1) = 0.3_dp; h(2, 2) = -0.7_dp; h(3, 3) = 0.2_dp; h(1, 2) = 0.4_dp; h(2, 1) = 0.1_dp
    f = identity3 + eps*h
    call hyperelastic_response(law, f, stress, tangent)
    d = elastic_matrix(2.0_dp*(law%c10 + law%c01), 2.0_dp/law%d1)
    strain = eps*[h(1, 1), h(2, 2), h(3, 3), h(1, 2) + h(2, 1)]
    ! stress ~ 1 Pa here; the O(eps) relative remainder is 1e-7 of it
    call check('small strain '//name//': stress is Hooke''s law', &
               maxval(abs(stress - matmul(d, strain))) <= 1.0e-6_dp*maxval(abs(matmul(d, strain))))
    call check('small strain '//name//': tangent is the elasticity matrix', &
               maxval(abs(tangent - d)) <= 1.0e-5_dp*maxval(abs(d)))
  end subroutine small_strain_limit

  !> A deformation gradient: rotation by angle, stretches l1, l2 in a frame at angle2, hoop l3.
  pure function gradient_of(angle, angle2, l1, l2, l3) result(f)
    real(dp), intent(in) :: angle, angle2, l1, l2, l3
    real(dp) :: f(3, 3), q(2, 2), p(2, 2), u(2, 2)
    q = reshape([cos(angle), sin(angle), -sin(angle), cos(angle)], [2, 2])
    p = reshape([cos(angle2), sin(angle2), -sin(angle2), cos(angle2)], [2, 2])
    u = matmul(p, matmul(reshape([l1, 0.0_dp, 0.0_dp, l2], [2, 2]), transpose(p)))
    f = 0.0_dp
    f(1:2, 1:2) = matmul(q, u)
    f(3, 3) = l3
  end function gradient_of

  pure real(dp) function determinant(a)
    real(dp), intent(in) :: a(3, 3)
    determinant = a(3, 3)*(a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1))
  end function determinant

  !> W at F (isochoric + volumetric).
  real(dp) function energy_at(law, f) result(w)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: stress(4), tangent(4, 4)
    call hyperelastic_response(law, f, stress, tangent, w)
  end function energy_at

  !> tau : H = dW/ds along F(s) = (1 + s H) F (central differences, step 1e-5: error O(s^2) ~ 1e-10 relative).
  subroutine stress_from_energy(law, name)
    type(hyperelastic_t), intent(in) :: law
    character(*), intent(in) :: name
    real(dp), parameter :: step = 1.0e-5_dp
    real(dp) :: f(3, 3), h(3, 3), stress(4), tangent(4, 4), power, difference, worst
    integer :: case
    worst = 0.0_dp
    do case = 1, 4
      select case (case)
      case (1); f = gradient_of(0.3_dp, 0.7_dp, 1.3_dp, 0.6_dp, 1.1_dp)
      case (2); f = gradient_of(-1.1_dp, 0.2_dp, 0.2_dp, 1.05_dp, 1.0_dp)
      case (3); f = gradient_of(0.0_dp, 0.0_dp, 0.9_dp, 0.9_dp, 0.9_dp)
      case default; f = gradient_of(2.0_dp, -0.4_dp, 1.8_dp, 0.5_dp, 0.7_dp)
      end select
      h = 0.0_dp
      h(1, 1) = 0.2_dp; h(2, 2) = -0.5_dp; h(3, 3) = 0.3_dp; h(1, 2) = 0.45_dp; h(2, 1) = -0.15_dp
      call hyperelastic_response(law, f, stress, tangent)
      ! Kirchhoff tau = J sigma; tau : H with H non-symmetric: the symmetric part counts
      power = determinant(f)*(stress(1)*h(1, 1) + stress(2)*h(2, 2) + stress(3)*h(3, 3) + stress(4)*(h(1, 2) + h(2, 1)))
      difference = (energy_at(law, matmul(identity3 + step*h, f)) - energy_at(law, matmul(identity3 - step*h, f)))/ &
                   (2.0_dp*step)
      worst = max(worst, abs(power - difference)/maxval(abs(determinant(f)*stress)))
    end do
    call check('stress = dW/dF '//name//' (4 deformations, to 1e-8 of the stress)', worst <= 1.0e-8_dp)
  end subroutine stress_from_energy

  !> J c : H = d tau/ds - H tau - tau H^T for a symmetric H (central differences, step 1e-6).
  subroutine tangent_from_stress(law, name)
    type(hyperelastic_t), intent(in) :: law
    character(*), intent(in) :: name
    real(dp), parameter :: step = 1.0e-6_dp
    real(dp) :: f(3, 3), h(3, 3), stress(4), tangent(4, 4), plus(4), minus(4), scratch(4, 4), tau(3, 3), rate(3, 3)
    real(dp) :: hv(4), expected(4), worst
    integer :: case, component
    worst = 0.0_dp
    do case = 1, 5
      select case (case)
      case (1); f = gradient_of(0.3_dp, 0.7_dp, 1.3_dp, 0.6_dp, 1.1_dp)
      case (2); f = gradient_of(-1.1_dp, 0.2_dp, 0.2_dp, 1.05_dp, 1.0_dp)
      case (3); f = gradient_of(0.5_dp, 0.0_dp, 0.8_dp, 0.8_dp, 0.8_dp)      ! equal stretches
      case (4); f = gradient_of(0.0_dp, 0.0_dp, 0.2_dp, 1.0_dp, 1.0_dp)      ! 80 % compression
      case default; f = gradient_of(2.0_dp, -0.4_dp, 1.8_dp, 0.5_dp, 0.7_dp)
      end select
      do component = 1, 4
        h = 0.0_dp
        select case (component)
        case (1); h(1, 1) = 1.0_dp
        case (2); h(2, 2) = 1.0_dp
        case (3); h(3, 3) = 1.0_dp
        case default; h(1, 2) = 0.5_dp; h(2, 1) = 0.5_dp
        end select
        hv = [h(1, 1), h(2, 2), h(3, 3), 2.0_dp*h(1, 2)]
        call hyperelastic_response(law, matmul(identity3 + step*h, f), plus, scratch)
        plus = plus*determinant(matmul(identity3 + step*h, f))
        call hyperelastic_response(law, matmul(identity3 - step*h, f), minus, scratch)
        minus = minus*determinant(matmul(identity3 - step*h, f))
        call hyperelastic_response(law, f, stress, tangent)
        tau = 0.0_dp
        tau(1, 1) = stress(1); tau(2, 2) = stress(2); tau(3, 3) = stress(3); tau(1, 2) = stress(4); tau(2, 1) = stress(4)
        tau = determinant(f)*tau
        rate = matmul(h, tau) + matmul(tau, transpose(h))
        expected = (plus - minus)/(2.0_dp*step) - [rate(1, 1), rate(2, 2), rate(3, 3), rate(1, 2)]
        worst = max(worst, maxval(abs(determinant(f)*matmul(tangent, hv) - expected))/ &
                           max(maxval(abs(determinant(f)*tangent)), 1.0_dp))
      end do
    end do
    call check('tangent = Oldroyd rate of tau '//name//' (5 deformations, 4 directions, to 1e-7)', worst <= 1.0e-7_dp)
  end subroutine tangent_from_stress

  !> Uniaxial stress along z (component 2) at stretch lambda: the lateral
  !> stretch from sigma_rr = 0 (bisection of the closed-form balance).
  real(dp) function lateral_stretch(law, lambda) result(lt)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: lambda
    real(dp) :: low, high
    integer :: i
    low = 0.05_dp
    high = 20.0_dp
    do i = 1, 200
      lt = 0.5_dp*(low + high)
      if (radial_balance(law, lambda, lt) > 0.0_dp) then
        high = lt
      else
        low = lt
      end if
    end do
  end function lateral_stretch

  !> J sigma_rr for b = diag(lt^2, lambda^2, lt^2), neo-Hookean: 2 C10 J^(-2/3) (lt^2 - I1/3) + J p(J); increasing in lt.
  pure real(dp) function radial_balance(law, lambda, lt) result(value)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: lambda, lt
    real(dp) :: j
    j = lambda*lt**2
    value = 2.0_dp*law%c10*j**(-2.0_dp/3.0_dp)*(lt**2 - (lambda**2 + 2.0_dp*lt**2)/3.0_dp) + &
            j*2.0_dp*(j - 1.0_dp)/law%d1
  end function radial_balance

  subroutine uniaxial_compression()
    type(hyperelastic_t) :: nearly_incompressible
    real(dp) :: lambda, lt, f(3, 3), stress(4), tangent(4, 4), expected, worst, worst_lateral, worst_limit, j
    integer :: k
    worst = 0.0_dp
    worst_lateral = 0.0_dp
    do k = 0, 16
      lambda = 1.0_dp - 0.05_dp*k                         ! 1 ... 0.2: 80 % compression
      lt = lateral_stretch(neo, lambda)
      f = 0.0_dp
      f(1, 1) = lt; f(2, 2) = lambda; f(3, 3) = lt
      call hyperelastic_response(neo, f, stress, tangent)
      j = lambda*lt**2
      expected = 2.0_dp*neo%c10*j**(-5.0_dp/3.0_dp)*(lambda**2 - lt**2)
      worst = max(worst, abs(stress(2) - expected)/max(abs(expected), 1.0_dp))
      worst_lateral = max(worst_lateral, max(abs(stress(1)), abs(stress(3)))/max(abs(expected), 1.0_dp))
    end do
    ! bisection to 2^-200: the root is exact to round-off; the stress difference ~1e-15
    call check('uniaxial compression to 80 %: sigma_zz = 2 C10 J^(-5/3) (lambda^2 - lambda_t^2)', worst <= 1.0e-12_dp)
    call check('uniaxial compression to 80 %: the lateral stresses vanish', worst_lateral <= 1.0e-12_dp)
    ! K / G = 1e5: lambda_t = lambda^(-1/2) and sigma = 2 C10 (lambda^2 - 1/lambda) to O(G/K)
    nearly_incompressible = hyperelastic_t(c10=0.5_dp*shear, c01=0.0_dp, d1=2.0_dp/(1.0e5_dp*shear))
    worst_limit = 0.0_dp
    do k = 1, 16
      lambda = 1.0_dp - 0.05_dp*k
      lt = lateral_stretch(nearly_incompressible, lambda)
      f = 0.0_dp
      f(1, 1) = lt; f(2, 2) = lambda; f(3, 3) = lt
      call hyperelastic_response(nearly_incompressible, f, stress, tangent)
      expected = 2.0_dp*nearly_incompressible%c10*(lambda**2 - 1.0_dp/lambda)
      worst_limit = max(worst_limit, abs(stress(2) - expected)/abs(expected))
    end do
    call check('nearly incompressible uniaxial: sigma = 2 C10 (lambda^2 - 1/lambda) to 1e-4 (G/K = 1e-5)', &
               worst_limit <= 1.0e-4_dp, 'worst relative error above 1e-4')
  end subroutine uniaxial_compression

  subroutine objectivity()
    real(dp) :: f(3, 3), q(3, 3), s(4), sq(4), t(4, 4), tq(4, 4), sigma(3, 3), rotated(3, 3)
    f = gradient_of(0.4_dp, 0.9_dp, 1.4_dp, 0.5_dp, 0.8_dp)
    q = gradient_of(1.1_dp, 0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp)
    call hyperelastic_response(mooney, f, s, t)
    call hyperelastic_response(mooney, matmul(q, f), sq, tq)
    sigma = 0.0_dp
    sigma(1, 1) = s(1); sigma(2, 2) = s(2); sigma(3, 3) = s(3); sigma(1, 2) = s(4); sigma(2, 1) = s(4)
    rotated = matmul(q, matmul(sigma, transpose(q)))
    call check('objectivity: sigma(Q F) = Q sigma(F) Q^T', &
               maxval(abs(sq - [rotated(1, 1), rotated(2, 2), rotated(3, 3), rotated(1, 2)])) <= 1.0e-9_dp*maxval(abs(s)))
  end subroutine objectivity

  function flesh(kind) result(material)
    integer, intent(in) :: kind
    type(material_t) :: material
    material%shear = shear
    material%bulk = bulk
    material%hyperelastic = kind
    material%c10 = 0.35_dp*shear
    material%c01 = merge(0.15_dp*shear, 0.0_dp, kind == hyperelastic_mooney_rivlin)
    if (kind == hyperelastic_neo_hooke) material%c10 = 0.5_dp*shear
    material%d1 = 2.0_dp/bulk
  end function flesh

  !> K against central differences of f (step 1e-8 of the element size: error ~1e-7 relative).
  subroutine element_tangent()
    real(dp), parameter :: xy(2, 4) = reshape([0.01_dp, 0.0_dp, 0.022_dp, 0.001_dp, 0.025_dp, 0.013_dp, &
                                               0.008_dp, 0.011_dp], [2, 4])
    real(dp) :: u(8), force(8), stiffness(8, 8), plus(8), minus(8), scratch(8, 8), stress(4, 4), strain(4, 4)
    real(dp) :: energy, numeric(8, 8), step
    integer :: geometry, formulation, kind, column, trial
    logical :: valid
    character(len=80) :: name
    u = [0.002_dp, -0.003_dp, -0.001_dp, -0.004_dp, 0.003_dp, -0.006_dp, 0.001_dp, -0.002_dp]
    step = 1.0e-9_dp
    do trial = 1, 8
      geometry = merge(geometry_axisymmetric, geometry_plane_strain, trial <= 4)
      formulation = merge(formulation_standard, formulation_bbar, mod(trial - 1, 4) < 2)
      kind = merge(hyperelastic_neo_hooke, hyperelastic_mooney_rivlin, mod(trial, 2) == 1)
      call element_response(geometry, formulation, flesh(kind), xy, u, .true., force, stiffness, stress, strain, &
                            energy, valid)
      do column = 1, 8
        call element_response(geometry, formulation, flesh(kind), xy, u + step*unit(column), .false., plus, scratch, &
                              stress, strain, energy, valid)
        call element_response(geometry, formulation, flesh(kind), xy, u - step*unit(column), .false., minus, scratch, &
                              stress, strain, energy, valid)
        numeric(:, column) = (plus - minus)/(2.0_dp*step)
      end do
      write(name, '(a, a, a, a)') 'element tangent = df/du: ', trim(merge('axisymmetric ', 'plane strain ', &
        geometry == geometry_axisymmetric)), &
        trim(merge(' pointwise      ', ' mean dilatation', formulation == formulation_standard)), &
        trim(merge(' neo-Hookean  ', ' Mooney-Rivlin', kind == hyperelastic_neo_hooke))
      call check(trim(name)//' (to 1e-6)', maxval(abs(stiffness - numeric)) <= 1.0e-6_dp*maxval(abs(stiffness)))
      call check(trim(name)//' is symmetric', maxval(abs(stiffness - transpose(stiffness))) <= &
                 1.0e-12_dp*maxval(abs(stiffness)))
    end do
  end subroutine element_tangent

  pure function unit(k) result(e)
    integer, intent(in) :: k
    real(dp) :: e(8)
    e = 0.0_dp
    e(k) = 1.0_dp
  end function unit

  !> u = (F0 - I) X for a homogeneous F0 (axisymmetric: F0 diagonal, r -> a r,
  !> z -> c z + d r is not axisymmetric-homogeneous, so diagonal only; plane
  !> strain: a general F0): every point's F is F0, the stresses equal the
  !> law's at F0, and the log strain that of F0.
  subroutine patch_test()
    real(dp), parameter :: xy(2, 4) = reshape([0.01_dp, 0.0_dp, 0.022_dp, 0.001_dp, 0.025_dp, 0.013_dp, &
                                               0.008_dp, 0.011_dp], [2, 4])
    real(dp) :: f0(3, 3), u(8), force(8), stiffness(8, 8), stress(4, 4), strain(4, 4), energy, expected(4), tangent(4, 4)
    real(dp) :: worst
    integer :: a, geometry, formulation
    logical :: valid
    type(finite_point_t) :: points(4)
    do geometry = 1, 2
      f0 = 0.0_dp
      if (geometry == geometry_axisymmetric) then
        f0(1, 1) = 1.3_dp; f0(2, 2) = 0.35_dp; f0(3, 3) = 1.3_dp
      else
        f0(1, 1) = 1.2_dp; f0(1, 2) = 0.3_dp; f0(2, 1) = -0.1_dp; f0(2, 2) = 0.4_dp; f0(3, 3) = 1.0_dp
      end if
      do a = 1, 4
        u(2*a - 1:2*a) = matmul(f0(1:2, 1:2), xy(:, a)) - xy(:, a)
      end do
      call finite_kinematics(geometry, xy, u, points, valid)
      worst = 0.0_dp
      do a = 1, 4
        worst = max(worst, maxval(abs(points(a)%deformation - f0)))
      end do
      call check('patch: F at every Gauss point is the homogeneous F0 ('//trim(merge('axisymmetric', 'plane strain', &
                 geometry == geometry_axisymmetric))//')', valid .and. worst <= 1.0e-13_dp)
      do formulation = 1, 2
        call element_response(geometry, formulation, flesh(hyperelastic_neo_hooke), xy, u, .false., force, stiffness, &
                              stress, strain, energy, valid)
        call hyperelastic_response(hyperelastic_t(c10=0.5_dp*shear, c01=0.0_dp, d1=2.0_dp/bulk), f0, expected, tangent)
        worst = 0.0_dp
        do a = 1, 4
          worst = max(worst, maxval(abs(stress(:, a) - expected)))
        end do
        call check('patch: the stress is the law''s at F0 at every point ('//trim(merge('pointwise      ', &
                   'mean dilatation', formulation == formulation_standard))//', geometry '//achar(48 + geometry)//')', &
                   worst <= 1.0e-9_dp*maxval(abs(expected)))
        worst = 0.0_dp
        do a = 1, 4
          worst = max(worst, maxval(abs(strain(:, a) - logarithmic_strain(f0))))
        end do
        call check('patch: the log strain is that of F0 (geometry '//achar(48 + geometry)//')', worst <= 1.0e-13_dp)
      end do
    end do
    ! log strain of a pure stretch: ln(lambda) on the diagonal
    f0 = 0.0_dp
    f0(1, 1) = 0.2_dp; f0(2, 2) = 1.5_dp; f0(3, 3) = 0.9_dp
    call check('log strain of a stretch: (ln 0.2, ln 1.5, ln 0.9, 0)', maxval(abs(logarithmic_strain(f0) - &
               [log(0.2_dp), log(1.5_dp), log(0.9_dp), 0.0_dp])) <= 1.0e-14_dp)
  end subroutine patch_test

  !> Plane strain, u = (Q - I) X for a rotation Q of 60 degrees: F = Q, no stress, no strain, no force.
  subroutine rigid_rotation()
    real(dp), parameter :: xy(2, 4) = reshape([0.01_dp, 0.0_dp, 0.022_dp, 0.001_dp, 0.025_dp, 0.013_dp, &
                                               0.008_dp, 0.011_dp], [2, 4])
    real(dp) :: q(2, 2), u(8), force(8), stiffness(8, 8), stress(4, 4), strain(4, 4), energy, angle
    integer :: a
    logical :: valid
    angle = acos(-1.0_dp)/3.0_dp
    q = reshape([cos(angle), sin(angle), -sin(angle), cos(angle)], [2, 2])
    do a = 1, 4
      u(2*a - 1:2*a) = matmul(q, xy(:, a)) - xy(:, a)
    end do
    call element_response(geometry_plane_strain, formulation_standard, flesh(hyperelastic_mooney_rivlin), xy, u, &
                          .false., force, stiffness, stress, strain, energy, valid)
    call check('rigid rotation of 60 degrees: no stress', valid .and. maxval(abs(stress)) <= 1.0e-9_dp*shear)
    ! W from I1bar - 3 and I2bar - 3 at round-off (~1e-15) times C10 over the element's 1.4e-4 m^2
    call check('rigid rotation: no strain, no energy', maxval(abs(strain)) <= 1.0e-14_dp .and. &
               abs(energy) <= 1.0e-14_dp*shear*1.4e-4_dp)
    call check('rigid rotation: no internal force', maxval(abs(force)) <= 1.0e-9_dp*shear*1.0e-4_dp)
  end subroutine rigid_rotation
end program test_finite
