!> Warnings about a deck that runs but whose answer may be poor: the time
!> step against the shortest physical times of the scene (before the run),
!> and the energy balance of a dynamic run (after it). They are counted in
!> the summary's `warnings` with the deck's own warnings.
!>
!> The physical times of a scene:
!> - the Hertz contact duration of an impact on the plate, eqs. [43], [44]:
!>   t_c = 2 x 1.4716 alpha_m/V with alpha_m = (15 M V^2/(16 E* sqrt(R)))^(2/5),
!>   E* = E/(1 - nu^2) (instantaneous constants), for a generated round body
!>   of one material (MESH SPHERE, SPHEROID or OUTLINE) moving at V toward
!>   the plate, R its radius of
!>   curvature at the contact pole (`pole_curvature_radius`), M its mass;
!> - the wave transit of the pole element (the element at the point of first
!>   contact): its smallest side over the dilatational wave speed
!>   c_p = sqrt((K + 4 G/3)/rho) (instantaneous moduli);
!> - the wave transit of the body: its height over c_p, the order of the
!>   period of its lowest vibration modes.
!>
!> The warnings and their levels, measured on the Table 1 impact (level 1):
!> - fewer than `contact_steps_minimum` = 20 steps in the Hertz contact: at 16
!>   steps (DT = 0.2 ms) alpha_m is 0.3 %, t_m 0.8 %, q_m 5 % off the
!>   DT = 0.01 ms values and the energy balance is off by 1.0 % of the input;
!>   at 3 steps (DT = 1 ms) alpha_m is +29 %, t_m +31 %, q_m +37 %, balance 125 %.
!>   The study of accuracy against cost finds alpha, t and q within 1 % at
!>   80 steps (DT = 0.04 ms), the cheapest accurate choice.
!> - DT above the wave transit of the body: the body's own lowest modes are
!>   not resolved (Wilson-theta damps them away), so stresses and
!>   accelerations in time are filtered, whatever the mesh.
!> - the energy-balance error above `balance_warning_level` = 5 % of the
!>   energy put in (stable runs at a resolved DT: 1e-14 to 8e-4; DT = 0.4 ms:
!>   2.3 %; DT = 1 ms: 125 %).
!> The pole element's transit is reported (by `visco2d check`) but
!> does not warn: Wilson-theta is unconditionally stable for theta >= 1.37,
!> and a DT of many pole transits is the accurate and cheap choice of an
!> impact on a fine mesh (level 5 at DT = 0.04 ms: about 40 transits, alpha,
!> t and q within 1 %); only the stress wave the first contact sends into the
!> body is smoothed.
module visco2d_advice
  use visco2d_kinds, only: dp, pi, geometry_axisymmetric, kinematics_large
  use visco2d_strings, only: integer_text, message_real, compact_real
  use visco2d_deck, only: deck_t, warning_t, analysis_dynamic, initial_velocity
  use visco2d_record, only: record_t, record_warn, record_real
  use visco2d_contact, only: hertz_impact, hertz_t
  use visco2d_pad_mesh, only: body_nodes, body_elements
  use visco2d_mesh, only: pole_curvature_radius, generated_round_body
  implicit none
  private

  public :: time_scales_t, time_scales, time_step_warnings, energy_balance_warning
  public :: deformation_warnings, largest_strain
  public :: contact_steps_minimum, balance_warning_level, strain_warning_level, approach_warning_level, &
            speed_warning_level

  !> Fewer steps than this in the Hertz contact duration warn.
  integer, parameter :: contact_steps_minimum = 20
  !> An energy-balance error above this fraction of the energy put in warns.
  real(dp), parameter :: balance_warning_level = 0.05_dp
  !> A principal strain above this magnitude is beyond the small-strain model:
  !> the quadratic term of the Green-Lagrange strain, e^2/2, is then 10 % of
  !> the strain. Hertz contact strains are of the order of a/R, so the paper's
  !> impacts already reach 8 to 16 % at the pole element (Table 1, Table 2,
  !> the apples at level 1: measured); the warning is for what lies well
  !> beyond them (a drop of several metres, a soft fruit hit hard).
  real(dp), parameter :: strain_warning_level = 0.20_dp
  !> An approach alpha_max above this fraction of the sphere's radius warns:
  !> there the small-strain answer is measured to be 1 % short in alpha_max
  !> against a finite-deformation (neo-Hookean, NLGEOM) reference of the
  !> Table 1 sphere (doc/calculix_nlgeom.md: -0.51 % at alpha/R = 0.029,
  !> -1.03 % at 0.047), with the peak force some 1-2 % high and the peak
  !> subsurface shear 10 % low. The paper's apple at 1.2 m/s reaches 6.2 %.
  real(dp), parameter :: approach_warning_level = 0.045_dp
  !> The measured small-strain errors (visco2d small strain against CalculiX
  !> neo-Hookean with NLGEOM on the same mesh, level 2; doc/small_strain_error.csv):
  !> alpha/R and the relative errors of alpha_max, the peak force and the
  !> peak shear at alpha_max.
  real(dp), parameter :: measured_approach(6) = [0.019473_dp, 0.028755_dp, 0.047131_dp, 0.073718_dp, &
                                                  0.10768_dp, 0.14077_dp]
  real(dp), parameter :: measured_alpha_error(6) = [-0.0037496_dp, -0.0050601_dp, -0.010311_dp, -0.011462_dp, &
                                                     -0.01078_dp, -0.015727_dp]
  real(dp), parameter :: measured_force_error(6) = [0.0096889_dp, 0.023734_dp, 0.012274_dp, 0.022356_dp, &
                                                     0.0069867_dp, 0.034138_dp]
  real(dp), parameter :: measured_shear_error(6) = [-0.057815_dp, -0.060902_dp, -0.096919_dp, -0.10622_dp, &
                                                     -0.10088_dp, -0.13881_dp]
  !> An impact speed above this (m/s; a drop of 3 m) is far above fruit
  !> handling and is warned about as a possible unit slip (cm read as m).
  real(dp), parameter :: speed_warning_level = 7.7_dp

  !> The physical times of a scene, s (0 when the scene does not have one).
  type :: time_scales_t
    real(dp) :: contact_duration = 0.0_dp  !< Hertz contact duration of the impact
    real(dp) :: pole_transit = 0.0_dp      !< wave transit of the pole element
    real(dp) :: body_transit = 0.0_dp      !< wave transit of the body (its height)
    real(dp) :: wave_speed = 0.0_dp        !< c_p, m/s, of the pole element's material
  end type time_scales_t

contains

  !> The physical times of a dynamic scene with a plate (all 0 otherwise;
  !> body_transit also without a plate).
  function time_scales(deck) result(scales)
    type(deck_t), intent(in) :: deck
    type(time_scales_t) :: scales
    type(hertz_t) :: hertz
    real(dp) :: speed, height, radius
    integer :: pole_element
    if (deck%analysis /= analysis_dynamic .or. deck%mesh%nelem == 0) return
    height = maxval(deck%mesh%xy(2, :body_nodes(deck))) - minval(deck%mesh%xy(2, :body_nodes(deck)))   ! not a PAD's
    pole_element = first_contact_element(deck)
    scales%wave_speed = wave_speed(deck, max(pole_element, 1))
    if (scales%wave_speed > 0.0_dp) scales%body_transit = height/scales%wave_speed
    if (deck%plate%line == 0 .or. pole_element == 0) return
    if (scales%wave_speed > 0.0_dp) scales%pole_transit = smallest_side(deck, pole_element)/scales%wave_speed
    if (.not. allocated(deck%mesh%source)) return
    if (.not. generated_round_body(deck%mesh) .or. size(deck%materials) /= 1 .or. deck%pad%line > 0) return
    associate (velocity => initial_velocity(deck))
    speed = -velocity(2)                                 ! toward the plate below
    end associate
    if (.not. (speed > 0.0_dp)) return
    radius = pole_curvature_radius(deck%mesh, body_elements(deck))
    if (.not. (radius > 0.0_dp)) return
    associate (material => deck%materials(1))
    hertz = hertz_impact(material%young, material%poisson, radius, body_mass(deck), speed)
    end associate
    if (hertz%duration > 0.0_dp .and. hertz%duration < huge(1.0_dp)) scales%contact_duration = hertz%duration
  end function time_scales

  !> Warnings about DT against the scene's physical times, into deck%warnings
  !> (located at the TIME card of each stage concerned).
  subroutine time_step_warnings(deck)
    type(deck_t), intent(inout) :: deck
    type(time_scales_t) :: scales
    integer :: k
    real(dp) :: steps
    scales = time_scales(deck)
    if (.not. allocated(deck%stages)) return
    do k = 1, size(deck%stages)
      associate (dt => deck%stages(k)%dt, line => deck%stages(k)%line)
      if (scales%contact_duration > 0.0_dp) then
        steps = scales%contact_duration/dt
        if (steps < real(contact_steps_minimum, dp)) call add(line, 'DT = '//message_real(dt)//' s leaves only '// &
          integer_text(int(steps))//' steps in the Hertz contact duration of this impact (' &
            //message_real(scales%contact_duration)// &
          ' s): use at least '//integer_text(contact_steps_minimum)//' (DT <= '// &
          message_real(scales%contact_duration/contact_steps_minimum)//' s); fewer overestimate alpha_m and t_m '// &
          '(+29 % at 3 steps on the Table 1 sphere)')
      end if
      if (scales%body_transit > 0.0_dp .and. dt > scales%body_transit) call add(line, 'DT = '//message_real(dt)// &
        ' s is longer than the time a stress wave takes to cross the body ('//message_real(scales%body_transit)// &
        ' s at c_p = '//message_real(scales%wave_speed)//' m/s): its lowest vibration modes are not resolved '// &
        '(Wilson-theta damps them), so stresses and accelerations in time are filtered')
      end associate
    end do
    call speed_warning()
  contains
    !> A drop or initial speed far above fruit handling: a unit slip?
    subroutine speed_warning()
      real(dp) :: speed
      integer :: line
      character(:), allocatable :: card
      type(warning_t) :: warning
      if (deck%analysis /= analysis_dynamic) return
      speed = norm2(initial_velocity(deck))
      if (.not. (speed > speed_warning_level)) return
      if (deck%dynamics%drop_line > 0) then
        line = deck%dynamics%drop_line
        card = 'DROP'
      else
        line = deck%dynamics%initial_line
        card = 'INITIAL'
      end if
      warning%text = deck%cards%file//':'//integer_text(line)//': '//card//': the impact speed '//message_real(speed)// &
        ' m/s (a drop of '//message_real(speed**2/(2.0_dp*9.80665_dp))//' m) is far above fruit handling (drops below '// &
        'about 1 m, 4.4 m/s); a height or speed in the wrong unit (cm for m)?'
      deck%warnings = [deck%warnings, warning]
    end subroutine speed_warning

    subroutine add(line, message)
      integer, intent(in) :: line
      character(*), intent(in) :: message
      type(warning_t) :: warning
      warning%text = deck%cards%file//':'//integer_text(line)//': TIME: '//message
      deck%warnings = [deck%warnings, warning]
    end subroutine add
  end subroutine time_step_warnings

  !> After a dynamic run: the text of a warning (else '') when the largest
  !> energy-balance error (`relative`, of the energy put in) exceeds
  !> balance_warning_level; `line` is that of the first TIME card.
  subroutine energy_balance_warning(deck, relative, message, line)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: relative
    character(:), allocatable, intent(out) :: message
    integer, intent(out) :: line
    message = ''
    line = 0
    if (.not. (relative > balance_warning_level)) return
    if (allocated(deck%stages)) then
      if (size(deck%stages) > 0) line = deck%stages(1)%line
    end if
    message = 'the energy balance is off by '//message_real(100.0_dp*relative)//' % of the energy put into the body '// &
      '(above '//message_real(100.0_dp*balance_warning_level)//' %): the time integration is inaccurate; a smaller DT '// &
      'brings it down (stable runs at a resolved DT stay below 0.1 %)'
  end subroutine energy_balance_warning

  !> The element holding the node nearest the plate (the point of first contact); 0 if none.
  integer function first_contact_element(deck) result(element)
    type(deck_t), intent(in) :: deck
    integer :: node
    element = 0
    if (deck%plate%line == 0) then
      node = minloc(deck%mesh%xy(2, :), dim=1)
    else
      node = minloc(abs(deck%mesh%xy(2, :) - deck%plate%z) + abs(deck%mesh%xy(1, :))*epsilon(1.0_dp), dim=1)
    end if
    do element = 1, deck%mesh%nelem
      if (any(deck%mesh%connectivity(:, element) == node)) return
    end do
    element = 0
  end function first_contact_element

  !> c_p = sqrt((K + 4 G/3)/rho) of an element's material (instantaneous), m/s.
  real(dp) function wave_speed(deck, element)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: element
    wave_speed = 0.0_dp
    associate (material => deck%materials(deck%mesh%element_material(element)))
    if (material%density > 0.0_dp) &
      wave_speed = sqrt((material%bulk + 4.0_dp/3.0_dp*material%shear)/material%density)
    end associate
  end function wave_speed

  !> The shortest side of an element, m.
  real(dp) function smallest_side(deck, element)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: element
    integer :: k
    smallest_side = huge(1.0_dp)
    do k = 1, 4
      associate (a => deck%mesh%connectivity(k, element), b => deck%mesh%connectivity(mod(k, 4) + 1, element))
      smallest_side = min(smallest_side, norm2(deck%mesh%xy(:, a) - deck%mesh%xy(:, b)))
      end associate
    end do
  end function smallest_side

  !> The mass of the whole body (not a PAD), kg: rho times each element's
  !> volume (Pappus: 2 pi r_centroid A in axisymmetry, A per metre in plane strain).
  real(dp) function body_mass(deck)
    type(deck_t), intent(in) :: deck
    real(dp) :: area, moment, x(4), y(4)
    integer :: e, k, next
    body_mass = 0.0_dp
    do e = 1, body_elements(deck)
      x = deck%mesh%xy(1, deck%mesh%connectivity(:, e))
      y = deck%mesh%xy(2, deck%mesh%connectivity(:, e))
      area = 0.0_dp
      moment = 0.0_dp
      do k = 1, 4
        next = mod(k, 4) + 1
        area = area + 0.5_dp*(x(k)*y(next) - x(next)*y(k))
        moment = moment + (x(k) + x(next))*(x(k)*y(next) - x(next)*y(k))/6.0_dp
      end do
      associate (density => deck%materials(deck%mesh%element_material(e))%density)
      if (deck%settings%geometry == geometry_axisymmetric) then
        body_mass = body_mass + density*2.0_dp*pi*moment
      else
        body_mass = body_mass + density*area
      end if
      end associate
    end do
  end function body_mass
  !> After a dynamic run: warnings (into the record, counted) when the
  !> deformation is beyond the small-strain, small-displacement model: a
  !> principal strain above strain_warning_level (`strain`: the largest over
  !> the body's elements, `pad_strain` over a PAD's, each located at its
  !> material's card), or for a generated round body on the plate an approach
  !> alpha_max above approach_warning_level of R (its pole curvature radius).
  !> None with KINEMATICS LARGE: the run is then not small-strain.
  subroutine deformation_warnings(deck, record, strain, pad_strain)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: strain, pad_strain
    real(dp) :: alpha, radius
    integer :: k, line
    logical :: found
    if (deck%settings%kinematics == kinematics_large) return   ! finite deformation: no small-strain error to warn of
    if (strain > strain_warning_level) then
      line = 0
      if (allocated(deck%materials)) then
        if (size(deck%materials) > 0) line = deck%materials(deck%mesh%element_material(1))%line
      end if
      call record_warn(record, 'the largest principal strain reached '//message_real(100.0_dp*strain)//' % (above '// &
        message_real(100.0_dp*strain_warning_level)//' %): beyond the small-strain model, stresses and displacements '// &
        'are only indicative; KINEMATICS LARGE runs the deck at finite deformation (doc/finite.md)', &
        file=deck%cards%file, line=line, card='MATERIAL')
    end if
    if (pad_strain > strain_warning_level) call record_warn(record, 'the largest principal strain in the pad ('// &
      deck%pad%material//') reached '//message_real(100.0_dp*pad_strain)//' % (above '// &
      message_real(100.0_dp*strain_warning_level)//' %): beyond the small-strain, linear pad model (a foam buckles '// &
      'and densifies); its results are only indicative; a HYPERFOAM pad with KINEMATICS LARGE describes it '// &
      '(doc/hyperfoam.md)', file=deck%cards%file, line=deck%pad%line, card='PAD')
    if (deck%plate%line == 0 .or. .not. generated_round_body(deck%mesh)) return
    radius = pole_curvature_radius(deck%mesh, body_elements(deck))
    if (.not. (radius > 0.0_dp)) return
    do k = 1, record%nsummary
      if (trim(record%summary(k)%key) /= 'alpha_max_mm' .and. trim(record%summary(k)%key) /= 'alpha_largest_mm') cycle
      call record_real(record, record%summary(k)%key, alpha, found)
      if (.not. found) return
      alpha = 1.0e-3_dp*alpha
      if (alpha > approach_warning_level*radius) call record_warn(record, 'the approach alpha_max = '// &
        message_real(1.0e3_dp*alpha)//' mm is '//percent_text(alpha/radius)//' % of the radius (above '// &
        percent_text(approach_warning_level)//' %): '//small_strain_error_text(alpha/radius)// &
        '; KINEMATICS LARGE runs the deck at finite deformation (doc/finite.md)', &
        file=deck%cards%file, line=deck%plate%line, card='PLATE')
      return
    end do
  end subroutine deformation_warnings

  !> What the small-strain answer is measured to miss at an approach of
  !> `ratio` = alpha_max / R: the errors of measured_* interpolated
  !> linearly (the last row's beyond it, said so).
  function small_strain_error_text(ratio) result(text)
    real(dp), intent(in) :: ratio
    character(:), allocatable :: text
    real(dp) :: weight, alpha_error, force_error, shear_error
    integer :: k
    k = 1
    do while (k < size(measured_approach) - 1 .and. ratio > measured_approach(k + 1))
      k = k + 1
    end do
    weight = min(max((ratio - measured_approach(k))/(measured_approach(k + 1) - measured_approach(k)), 0.0_dp), 1.0_dp)
    alpha_error = measured_alpha_error(k) + weight*(measured_alpha_error(k + 1) - measured_alpha_error(k))
    force_error = measured_force_error(k) + weight*(measured_force_error(k + 1) - measured_force_error(k))
    shear_error = measured_shear_error(k) + weight*(measured_shear_error(k + 1) - measured_shear_error(k))
    text = 'against a finite-deformation (neo-Hookean) reference of an elastic sphere at this approach, the '// &
      'small-strain answer is measured '//percent_text(abs(alpha_error))//' % short in alpha_max, '// &
      percent_text(abs(force_error))//' % high in the peak force and '// &
      percent_text(abs(shear_error))//' % low in the peak subsurface shear'
    if (ratio > measured_approach(size(measured_approach))) text = text//' (measured up to '// &
      percent_text(measured_approach(size(measured_approach)))//' % of R; more beyond)'
    text = text//' (doc/calculix_nlgeom.md)'
  end function small_strain_error_text

  !> A fraction as a percentage to one decimal, as a person writes it (0.0103 -> '1', 0.0615 -> '6.2').
  pure function percent_text(fraction) result(text)
    real(dp), intent(in) :: fraction
    character(:), allocatable :: text
    text = compact_real(anint(1000.0_dp*fraction)/10.0_dp)
  end function percent_text

  !> The largest magnitude of a principal strain over the Gauss points of a
  !> strain field (4, gauss, elements: e_r, e_z, e_theta, gamma_rz).
  pure real(dp) function largest_strain(strain) result(largest)
    real(dp), intent(in) :: strain(:, :, :)
    real(dp) :: centre, radius
    integer :: g, e
    largest = 0.0_dp
    do e = 1, size(strain, 3)
      do g = 1, size(strain, 2)
        associate (er => strain(1, g, e), ez => strain(2, g, e), et => strain(3, g, e), gamma => strain(4, g, e))
        centre = 0.5_dp*(er + ez)
        radius = hypot(0.5_dp*(er - ez), 0.5_dp*gamma)
        largest = max(largest, abs(centre) + radius, abs(et))
        end associate
      end do
    end do
  end function largest_strain
end module visco2d_advice
