!> The physical range of every number a deck gives. A value outside its range
!> is refused where it is read, with the field's column, the range and the text
!> as written: `deck.inp:4:24: MATERIAL: E must be in [0.001, 1e14] Pa, got "1e308"`.
!>
!> The bounds are far beyond any fruit or engineering problem and keep every
!> product the solvers form far from overflow: with lengths <= 1e4 m,
!> moduli <= 1e14 Pa, densities <= 1e5 kg/m^3, speeds <= 1e4 m/s and steps
!> >= 1e-12 s, a stiffness is below 1e18 N/m, a mass below 1e17 kg, a kinetic
!> energy below 1e25 J and the Wilson-theta mass term 6/(theta dt)^2 M below
!> 1e42 N/m (the largest double is 1.8e308). A nonzero magnitude below a
!> quantity's `floor` is refused when the quantity is divided by later (a speed
!> of 4.9e-324 m/s would make the Hertz time alpha/V infinite); other
!> quantities have no floor. Subnormal numbers (below 2.2e-308 in magnitude)
!> are refused for every field by the card reader.
module visco2d_ranges
  use visco2d_kinds, only: dp
  use visco2d_strings, only: compact_real
  implicit none
  private

  public :: range_t, range_text, in_range
  public :: modulus_range, density_range, rate_range, speed_range, acceleration_range, gravity_range
  public :: length_range, drop_height_range, pressure_range, force_range, time_range, time_step_range
  public :: curve_factor_range, expected_value_range, tolerance_range, bulk_shear_ratio_limit
  public :: failure_stress_range, failure_energy_range, pad_length_range, max_coordinate
  public :: plastic_strain_range, hardening_slope_range

  !> Accepted values: lower <= value <= upper and, if floor > 0, |value| >= floor
  !> or (if zero) value = 0.
  type :: range_t
    real(dp) :: lower = 0.0_dp
    real(dp) :: upper = 0.0_dp
    real(dp) :: floor = 0.0_dp         !< smallest nonzero magnitude (0: none)
    character(len=12) :: unit = ''     !< SI unit as printed after the range
    logical :: zero = .true.           !< 0 is accepted (with a floor: besides the range)
  end type range_t

  !> E, G, K of MATERIAL and G, E of PRONY: the softest gel is ~10 Pa, diamond 1.2e12 Pa.
  type(range_t), parameter :: modulus_range = range_t(1.0e-3_dp, 1.0e14_dp, 0.0_dp, 'Pa')
  !> RHO: 0 (no mass: STATIC, QUASISTATIC) or from a thin gas to twice osmium (22,590 kg/m^3) x 4.
  type(range_t), parameter :: density_range = range_t(0.0_dp, 1.0e5_dp, 1.0e-3_dp, 'kg/m^3')
  !> BETA, ALPHA of PRONY: 0 (no memory) or relaxation times from 30,000 years to 1 ps.
  type(range_t), parameter :: rate_range = range_t(0.0_dp, 1.0e12_dp, 1.0e-12_dp, '1/s')
  !> VR, VZ of INITIAL (and the speed of DROP): the Hertz references divide by the speed.
  type(range_t), parameter :: speed_range = range_t(-1.0e4_dp, 1.0e4_dp, 1.0e-9_dp, 'm/s')
  !> AR, AZ of INITIAL.
  type(range_t), parameter :: acceleration_range = range_t(-1.0e8_dp, 1.0e8_dp, 0.0_dp, 'm/s^2')
  !> G of GRAVITY (acts in -z); a centrifuge reaches 1e6 m/s^2.
  type(range_t), parameter :: gravity_range = range_t(0.0_dp, 1.0e6_dp, 1.0e-6_dp, 'm/s^2')
  !> Coordinates and displacements: PLATE Z, PROBE R= Z=, FIX UR= UZ=.
  type(range_t), parameter :: length_range = range_t(-1.0e4_dp, 1.0e4_dp, 0.0_dp, 'm')
  !> Largest |coordinate| of a node, m (NODE cards, MESH generators) (lengths beyond the scale of any
  !> body keep every product of the solvers far from overflow).
  real(dp), parameter :: max_coordinate = 1.0e4_dp
  !> THICKNESS, WIDTH and SIZE of PAD: from a 1 micrometre film to 100 m.
  type(range_t), parameter :: pad_length_range = range_t(1.0e-6_dp, 1.0e2_dp, 0.0_dp, 'm', .false.)
  !> HEIGHT of DROP: V = sqrt(2 g h) is divided by in the Hertz references.
  type(range_t), parameter :: drop_height_range = range_t(0.0_dp, 1.0e3_dp, 1.0e-9_dp, 'm')
  !> P of PRESSURE (times its curve): 1e12 Pa is ten times the pressure at the Earth's centre.
  type(range_t), parameter :: pressure_range = range_t(-1.0e12_dp, 1.0e12_dp, 0.0_dp, 'Pa')
  !> FR, FZ of FORCE (times its curve); N per radian (axisymmetric) or per metre (plane strain).
  type(range_t), parameter :: force_range = range_t(-1.0e12_dp, 1.0e12_dp, 0.0_dp, 'N')
  !> TEND of TIME, curve times, FIELDS times: up to 30 years.
  type(range_t), parameter :: time_range = range_t(0.0_dp, 1.0e9_dp, 0.0_dp, 's')
  !> DT of TIME: 6/(theta dt)^2 multiplies the mass matrix.
  type(range_t), parameter :: time_step_range = range_t(1.0e-12_dp, 1.0e9_dp, 0.0_dp, 's')
  !> Values of a CURVE (a factor on the card's load or displacement).
  type(range_t), parameter :: curve_factor_range = range_t(-1.0e6_dp, 1.0e6_dp, 0.0_dp, '')
  !> Largest K/G (and G/K) of a material at t = 0: nu within 5e-7 of 0.5 (or
  !> 1e-6 of -1) would drown the shear stiffness in the round-off of the bulk one.
  real(dp), parameter :: bulk_shear_ratio_limit = 1.0e6_dp
  !> The value of EXPECT: a relative error divides by it, so not 0.
  type(range_t), parameter :: expected_value_range = range_t(-1.0e200_dp, 1.0e200_dp, 1.0e-200_dp, '', .false.)
  !> RTOL of EXPECT: from round-off to a factor 1000.
  type(range_t), parameter :: tolerance_range = range_t(1.0e-15_dp, 1.0e3_dp, 0.0_dp, '')
  !> STRESS and THRESHOLDS of BRUISE (a failure stress): positive, from a gel to steel x 100.
  type(range_t), parameter :: failure_stress_range = range_t(1.0e-3_dp, 1.0e12_dp, 0.0_dp, 'Pa')
  !> STRAIN of HARDENING: an equivalent plastic strain, 0 to 100 (far beyond any tissue's).
  type(range_t), parameter :: plastic_strain_range = range_t(0.0_dp, 1.0e2_dp, 0.0_dp, '')
  !> TANGENT of PLASTIC and SLOPE of PLASTIC TABLE: 0 (perfectly plastic) up to the largest modulus.
  type(range_t), parameter :: hardening_slope_range = range_t(0.0_dp, 1.0e14_dp, 0.0_dp, 'Pa')
  !> ENERGY and THRESHOLDS of BRUISE CRITERION=ENERGY (a failure energy density), positive.
  type(range_t), parameter :: failure_energy_range = range_t(1.0e-3_dp, 1.0e12_dp, 0.0_dp, 'J/m^3')

contains

  !> True if the value lies in the range.
  pure logical function in_range(value, range)
    real(dp), intent(in) :: value
    type(range_t), intent(in) :: range
    in_range = value >= range%lower .and. value <= range%upper
    if (value == 0.0_dp) then
      in_range = in_range .and. (range%zero .or. range%floor == 0.0_dp)
    else
      in_range = in_range .and. abs(value) >= range%floor
    end if
  end function in_range

  !> The range as a message says it: 'in [0.001, 1e14] Pa', '0 or in [0.001, 1e5] kg/m^3',
  !> '0 or of magnitude in [1e-9, 1e4] m/s', 'nonzero, of magnitude in [1e-200, 1e200]'.
  pure function range_text(range) result(text)
    type(range_t), intent(in) :: range
    character(:), allocatable :: text
    if (range%floor > 0.0_dp .and. range%lower == -range%upper) then
      text = 'of magnitude in ['//compact_real(range%floor)//', '//compact_real(range%upper)//']'
      if (range%zero) then
        text = '0 or '//text
      else
        text = 'nonzero, '//text
      end if
    else if (range%floor > 0.0_dp) then
      text = '0 or in ['//compact_real(range%floor)//', '//compact_real(range%upper)//']'
    else
      text = 'in ['//compact_real(range%lower)//', '//compact_real(range%upper)//']'
    end if
    if (len_trim(range%unit) > 0) text = text//' '//trim(range%unit)
  end function range_text
end module visco2d_ranges
