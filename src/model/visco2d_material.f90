!> The materials: isotropic elasticity split into deviatoric and volumetric
!> parts (eqs. [1]-[4], [8]-[9]), and the constants of the viscoelastic-in-
!> shear / elastic-in-bulk law (eqs. [10]-[12]): a shear relaxation modulus
!> phi1(t) = G_inf + sum_m G_m exp(-beta_m t). Terms with beta = 0 have no
!> memory and are folded into G_inf, so an elastic material is the
!> no-memory limit (G_inf = G, no Prony terms). The incremental update is in
!> visco2d_viscoelastic. A material with a PLASTIC card also carries the
!> hardening curve of its von Mises plasticity (hardening_t; the return
!> mapping is visco2d_plasticity's).
module visco2d_material
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: material_t, material_kind_elastic, material_kind_viscoelastic, material_kind_uniaxial
  public :: material_kind_name, has_memory, shear_relaxation_modulus
  public :: elastic_matrix, stress_from_strain
  public :: von_mises, max_shear, elastic_constants_from_e_nu
  public :: hardening_t, bilinear_hardening
  public :: hyperelastic_none, hyperelastic_neo_hooke, hyperelastic_mooney_rivlin, hyperelastic_foam
  public :: hyperelastic_name

  integer, parameter :: material_kind_elastic = 1       !< MATERIAL id ELASTIC
  integer, parameter :: material_kind_viscoelastic = 2  !< MATERIAL id VISCOELASTIC + PRONY G= BETA=
  integer, parameter :: material_kind_uniaxial = 3      !< MATERIAL id UNIAXIAL + PRONY E= ALPHA= (eq. [47])

  !> The strain energy of a hyperelastic material (KINEMATICS LARGE; with
  !> KINEMATICS SMALL its linearisation, the shear and bulk moduli below).
  integer, parameter :: hyperelastic_none = 0           !< not hyperelastic: linear (visco)elastic
  integer, parameter :: hyperelastic_neo_hooke = 1      !< MATERIAL id NEOHOOKE C10= D1= (or E= NU=)
  integer, parameter :: hyperelastic_mooney_rivlin = 2  !< MATERIAL id MOONEY C10= C01= D1=
  integer, parameter :: hyperelastic_foam = 3           !< MATERIAL id HYPERFOAM + OGDEN MU= ALPHA= NU= cards

  !> The uniaxial yield stress against the equivalent plastic strain: piecewise
  !> linear through the points, with `final_slope` beyond the last.
  type :: hardening_t
    real(dp), allocatable :: plastic_strain(:)   !< ebar_k, increasing, the first 0
    real(dp), allocatable :: stress(:)           !< sigma_k, Pa, the first the initial yield stress
    real(dp) :: final_slope = 0.0_dp             !< d sigma_y / d ebar beyond the last point, Pa
  end type hardening_t

  !> One material of the deck.
  type :: material_t
    character(:), allocatable :: id      !< the id used by MAT= (upper case)
    integer :: kind = material_kind_elastic
    real(dp) :: young = 0.0_dp           !< E, Pa
    real(dp) :: poisson = 0.0_dp         !< nu
    real(dp) :: shear = 0.0_dp           !< G = mu, Pa   (eq. [8])
    real(dp) :: bulk = 0.0_dp            !< K = k, Pa    (eq. [9])
    real(dp) :: density = 0.0_dp         !< rho, kg/m^3
    !> Viscoelastic shear (eq. [12]): G(t) = long_term_shear + sum prony_shear exp(-prony_rate t).
    !> `shear` above is the instantaneous modulus G(0); `young`, `poisson` are instantaneous too.
    real(dp) :: long_term_shear = 0.0_dp     !< G_inf, Pa (= shear for an elastic material)
    real(dp), allocatable :: prony_shear(:)  !< G_m, Pa, terms with memory (beta_m > 0) only
    real(dp), allocatable :: prony_rate(:)   !< beta_m, 1/s, increasing
    !> The uniaxial series of a UNIAXIAL material as given (eq. [47]), kept for the listing.
    real(dp), allocatable :: uniaxial_young(:)  !< E_i, Pa
    real(dp), allocatable :: uniaxial_rate(:)   !< alpha_i, 1/s
    integer :: line = 0                      !< line of the MATERIAL card
    integer :: card_column = 0               !< column of its K= (NU= for UNIAXIAL) field, for errors
    integer, allocatable :: prony_lines(:)   !< lines of its PRONY cards, in the order given
    !> Von Mises plasticity (a PLASTIC card after the MATERIAL card): the hardening curve.
    logical :: plastic = .false.
    type(hardening_t) :: hardening
    logical :: plastic_table = .false.       !< PLASTIC TABLE (HARDENING cards); else YIELD= TANGENT=
    real(dp) :: plastic_yield = 0.0_dp       !< Y of PLASTIC YIELD=, Pa (bilinear)
    real(dp) :: plastic_tangent = 0.0_dp     !< E_t of PLASTIC TANGENT=, Pa (bilinear)
    integer :: plastic_line = 0              !< line of the PLASTIC card
    integer :: plastic_column = 0            !< column of its TANGENT= field (TABLE for a table), for errors
    !> A hyperelastic material (hyperelastic_*): W = C10 (I1bar - 3) + C01 (I2bar - 3) + (J - 1)^2 / D1,
    !> or the hyperfoam's terms; shear and bulk above hold its small-strain moduli.
    integer :: hyperelastic = hyperelastic_none
    real(dp) :: c10 = 0.0_dp                 !< C10, Pa
    real(dp) :: c01 = 0.0_dp                 !< C01, Pa
    real(dp) :: d1 = 0.0_dp                  !< D1 = 2 / K, 1/Pa
    real(dp), allocatable :: foam_mu(:)      !< hyperfoam mu_i, Pa
    real(dp), allocatable :: foam_alpha(:)   !< hyperfoam alpha_i
    real(dp), allocatable :: foam_nu(:)      !< hyperfoam nu_i
    integer, allocatable :: foam_lines(:)    !< lines of its OGDEN cards
  end type material_t

contains

  !> The bilinear curve of a yield stress Y (Pa) and a tangent modulus E_t
  !> (Pa, 0 <= E_t < E) for the Young's modulus E (Pa): the plastic modulus
  !> H = E E_t / (E - E_t) beyond Y, so that a uniaxial test reads the slope E_t.
  pure function bilinear_hardening(yield, tangent, young) result(hardening)
    real(dp), intent(in) :: yield, tangent, young
    type(hardening_t) :: hardening
    hardening%plastic_strain = [0.0_dp]
    hardening%stress = [yield]
    hardening%final_slope = young*tangent/(young - tangent)
  end function bilinear_hardening

  pure function material_kind_name(kind) result(name)
    integer, intent(in) :: kind
    character(:), allocatable :: name
    select case (kind)
    case (material_kind_viscoelastic); name = 'VISCOELASTIC'
    case (material_kind_uniaxial); name = 'UNIAXIAL'
    case default; name = 'ELASTIC'
    end select
  end function material_kind_name

  !> The card word of a hyperelastic kind ('' for none).
  pure function hyperelastic_name(kind) result(name)
    integer, intent(in) :: kind
    character(:), allocatable :: name
    select case (kind)
    case (hyperelastic_neo_hooke); name = 'NEOHOOKE'
    case (hyperelastic_mooney_rivlin); name = 'MOONEY'
    case (hyperelastic_foam); name = 'HYPERFOAM'
    case default; name = ''
    end select
  end function hyperelastic_name

  !> True if the material has Prony terms with memory (beta > 0): it needs history.
  pure logical function has_memory(material)
    type(material_t), intent(in) :: material
    has_memory = .false.
    if (allocated(material%prony_rate)) has_memory = size(material%prony_rate) > 0
  end function has_memory

  !> Shear relaxation modulus phi1(t), eq. [12], Pa.
  pure real(dp) function shear_relaxation_modulus(material, t) result(modulus)
    type(material_t), intent(in) :: material
    real(dp), intent(in) :: t
    modulus = material%long_term_shear
    if (has_memory(material)) modulus = modulus + sum(material%prony_shear*exp(-material%prony_rate*t))
  end function shear_relaxation_modulus

  !> G and K from E and nu.
  pure subroutine elastic_constants_from_e_nu(young, poisson, shear, bulk)
    real(dp), intent(in) :: young, poisson
    real(dp), intent(out) :: shear, bulk
    shear = young / (2.0_dp*(1.0_dp + poisson))
    bulk = young / (3.0_dp*(1.0_dp - 2.0_dp*poisson))
  end subroutine elastic_constants_from_e_nu

  !> Stress-strain matrix for strain (e_r, e_z, e_theta, gamma_rz) from the split
  !> s_ij = 2 G e_ij (eq. [8]) and sigma = K theta (eq. [9]).
  pure function elastic_matrix(shear, bulk) result(d)
    real(dp), intent(in) :: shear, bulk
    real(dp) :: d(4, 4)
    real(dp) :: diagonal, off_diagonal
    diagonal = bulk + 4.0_dp*shear/3.0_dp
    off_diagonal = bulk - 2.0_dp*shear/3.0_dp
    d = 0.0_dp
    d(1:3, 1:3) = off_diagonal
    d(1, 1) = diagonal
    d(2, 2) = diagonal
    d(3, 3) = diagonal
    d(4, 4) = shear
  end function elastic_matrix

  !> Stress (sigma_r, sigma_z, sigma_theta, tau_rz) from strain, eqs. [1]-[4], [8]-[9].
  pure function stress_from_strain(shear, bulk, strain) result(stress)
    real(dp), intent(in) :: shear, bulk, strain(4)
    real(dp) :: stress(4)
    real(dp) :: volumetric, mean
    volumetric = strain(1) + strain(2) + strain(3)              ! eq. [4]
    mean = bulk*volumetric                                       ! eq. [9]
    stress(1:3) = mean + 2.0_dp*shear*(strain(1:3) - volumetric/3.0_dp)  ! eqs. [1], [2], [8]
    stress(4) = shear*strain(4)                                  ! s_rz = 2 G e_rz, gamma = 2 e_rz
  end function stress_from_strain

  !> von Mises equivalent stress of (sigma_r, sigma_z, sigma_theta, tau_rz).
  pure elemental function von_mises(sr, sz, st, trz) result(value)
    real(dp), intent(in) :: sr, sz, st, trz
    real(dp) :: value
    value = sqrt(0.5_dp*((sr - sz)**2 + (sz - st)**2 + (st - sr)**2) + 3.0_dp*trz**2)
  end function von_mises

  !> Maximum shear stress (sigma_1 - sigma_3)/2 over the three principal stresses.
  pure elemental function max_shear(sr, sz, st, trz) result(value)
    real(dp), intent(in) :: sr, sz, st, trz
    real(dp) :: value, centre, radius, p1, p2
    centre = 0.5_dp*(sr + sz)
    radius = sqrt((0.5_dp*(sr - sz))**2 + trz**2)
    p1 = centre + radius
    p2 = centre - radius
    value = 0.5_dp*(max(p1, p2, st) - min(p1, p2, st))
  end function max_shear
end module visco2d_material
