!> The Hertz reference of two elastic spheres head on (a BODY under the
!> first body): the impact of Hertz (1882) and Timoshenko and Goodier
!> (Theory of Elasticity, 1951, section 140) with the reduced radius, modulus and mass
!>   1/R* = 1/R1 + 1/R2,  1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
!>   1/m* = 1/m1 + 1/m2,
!> at the relative approach speed w = v2 - v1 at first contact: the
!> one-sphere-on-a-plate formulas of visco2d_hertz (eqs. [43]-[45]) with E
!> = E*, nu = 0, R = R*, M = m*, V = w. Its keys are the hertz_* keys of a
!> plate impact, with hertz_effective_modulus_Pa for E*
!> (doc/two_bodies.md).
module visco2d_two_bodies
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, geometry_tolerance
  use visco2d_strings, only: table_real
  use visco2d_deck, only: deck_t
  use visco2d_record, only: record_t, record_put, record_put_real
  use visco2d_mesh, only: pole_curvature_radius, generated_round_body
  use visco2d_hertz, only: hertz_t, hertz_impact
  implicit none
  private

  public :: two_body_hertz, put_two_body_hertz

contains

  !> The Hertz maxima of two spheres (E_i, nu_i, R_i, m_i) meeting at the relative speed w.
  pure function two_body_hertz(young, poisson, radius, mass, speed) result(hertz)
    real(dp), intent(in) :: young(2), poisson(2), radius(2), mass(2), speed
    type(hertz_t) :: hertz
    hertz = hertz_impact(effective_modulus(young, poisson), 0.0_dp, product(radius)/sum(radius), &
                         product(mass)/sum(mass), speed)
  end function two_body_hertz

  !> 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
  pure real(dp) function effective_modulus(young, poisson) result(modulus)
    real(dp), intent(in) :: young(2), poisson(2)
    modulus = 1.0_dp/sum((1.0_dp - poisson**2)/young)
  end function effective_modulus

  !> The hertz_* keys of two bodies: the first body a generated round body of
  !> one material (R1 its pole's radius of curvature), the second the BODY's
  !> sphere; masses m1, m2 (kg, whole bodies) and the approach speed w (m/s)
  !> at first contact. Left out, with hertz_reference saying why, as for
  !> a plate impact (visco2d_hertz).
  subroutine put_two_body_hertz(deck, record, mass1, mass2, speed)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: mass1, mass2, speed
    type(hertz_t) :: hertz
    real(dp) :: radius(2), young(2), poisson(2), reduced_radius, wave_speed
    integer :: first, last
    last = deck%pad%first_element - 1
    if (.not. allocated(deck%mesh%source) .or. .not. generated_round_body(deck%mesh)) return
    first = deck%mesh%element_material(1)
    if (any(deck%mesh%element_material(1:last) /= first)) then
      call record_put(record, 'hertz_reference', 'none: the first body has more than one material')
      return
    end if
    if (speed <= 0.0_dp) then
      call record_put(record, 'hertz_reference', 'none: the bodies touched at rest relative to each other')
      return
    end if
    radius = [pole_curvature_radius(deck%mesh, last), deck%body%radius]
    if (.not. (radius(1) > 0.0_dp)) return
    associate (one => deck%materials(first), two => deck%materials(deck%body%material_index))
    young = [one%young, two%young]
    poisson = [one%poisson, two%poisson]
    wave_speed = min(sqrt(one%young/max(one%density, tiny(1.0_dp))), sqrt(two%young/max(two%density, tiny(1.0_dp))))
    end associate
    if (.not. speed < wave_speed) then
      call record_put(record, 'hertz_reference', 'none: w = '//table_real(speed)//' m/s is not small against the '// &
                      'wave speed sqrt(E/rho) = '//table_real(wave_speed)//' m/s (Hertz impact is quasi-static)')
      return
    end if
    reduced_radius = product(radius)/sum(radius)
    hertz = two_body_hertz(young, poisson, radius, [mass1, mass2], speed)
    if (.not. all(ieee_is_finite([hertz%alpha_max, hertz%t_alpha_max, hertz%q_max, hertz%force_max, &
                                  hertz%contact_radius, hertz%duration]))) then
      call record_put(record, 'hertz_reference', 'none: not a finite number at w = '//table_real(speed)//' m/s')
      return
    end if
    if (hertz%alpha_max <= geometry_tolerance*reduced_radius .or. hertz%alpha_max >= reduced_radius) then
      call record_put(record, 'hertz_reference', 'none: alpha_m = '//table_real(hertz%alpha_max)//' m is not '// &
                      'between the round-off of the node positions and R* = '//table_real(reduced_radius)//' m')
      return
    end if
    call record_put(record, 'hertz_reference', 'two spheres head on: R*, E*, m* at the approach speed')
    call record_put_real(record, 'hertz_effective_modulus_Pa', effective_modulus(young, poisson))
    call record_put_real(record, 'hertz_radius_m', reduced_radius)
    call record_put_real(record, 'hertz_mass_kg', product([mass1, mass2])/(mass1 + mass2))
    call record_put_real(record, 'hertz_speed_m_s', speed)
    call record_put_real(record, 'hertz_alpha_max_mm', 1.0e3_dp*hertz%alpha_max)
    call record_put_real(record, 'hertz_t_alpha_max_ms', 1.0e3_dp*hertz%t_alpha_max)
    call record_put_real(record, 'hertz_q_max_MPa', 1.0e-6_dp*hertz%q_max)
    call record_put_real(record, 'hertz_force_max_N', hertz%force_max)
    call record_put_real(record, 'hertz_contact_radius_mm', 1.0e3_dp*hertz%contact_radius)
    call record_put_real(record, 'hertz_contact_duration_ms', 1.0e3_dp*hertz%duration)
  end subroutine put_two_body_hertz
end module visco2d_two_bodies
