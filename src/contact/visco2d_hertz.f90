!> The Hertz / Timoshenko-Goodier impact of an elastic sphere on a rigid
!> plate, eqs. [43]-[45], built in as the analytic reference of an impact,
!> and its keys in the summary (hertz_*).
module visco2d_hertz
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, pi, geometry_tolerance, hertz_time_constant
  use visco2d_strings, only: table_real
  use visco2d_deck, only: deck_t
  use visco2d_record, only: record_t, record_put, record_put_real
  use visco2d_mesh, only: pole_curvature_radius, generated_round_body
  implicit none
  private

  public :: hertz_t, hertz_impact, put_hertz_summary, hertz_time_constant, hertz_duration_constant

  !> Contact duration 2 t_m = 2.9432 alpha_m / V.
  real(dp), parameter :: hertz_duration_constant = 2.0_dp*hertz_time_constant

  !> Hertz impact of an elastic sphere on a rigid plate (Timoshenko and
  !> Goodier), SI units.
  type :: hertz_t
    real(dp) :: alpha_max = 0.0_dp       !< m, eq. [43]
    real(dp) :: t_alpha_max = 0.0_dp     !< s, eq. [44] with 1.4716
    real(dp) :: q_max = 0.0_dp           !< Pa, eq. [45]
    real(dp) :: force_max = 0.0_dp       !< N, (4/3) E/(1 - nu^2) sqrt(R) alpha_m^(3/2)
    real(dp) :: contact_radius = 0.0_dp  !< m, sqrt(R alpha_m)
    real(dp) :: duration = 0.0_dp        !< s, 2.9432 alpha_m / V
  end type hertz_t

contains

  !> Eqs. [43]-[45]: the maxima of a Hertz impact at speed V of a sphere of
  !> mass M and radius R (E, nu) on a rigid plate.
  pure function hertz_impact(young, poisson, radius, mass, speed) result(hertz)
    real(dp), intent(in) :: young, poisson, radius, mass, speed
    type(hertz_t) :: hertz
    real(dp) :: modulus
    modulus = young/(1.0_dp - poisson**2)
    hertz%alpha_max = (15.0_dp*mass*speed**2/(16.0_dp*modulus*sqrt(radius)))**0.4_dp      ! eq. [43]
    hertz%t_alpha_max = hertz_time_constant*hertz%alpha_max/abs(speed)                   ! eq. [44]
    hertz%q_max = 2.0_dp*modulus/pi*sqrt(hertz%alpha_max/radius)                         ! eq. [45]
    hertz%force_max = 4.0_dp/3.0_dp*modulus*sqrt(radius)*hertz%alpha_max**1.5_dp
    hertz%contact_radius = sqrt(radius*hertz%alpha_max)
    hertz%duration = hertz_duration_constant*hertz%alpha_max/abs(speed)
  end function hertz_impact

  !> The Hertz reference of an impact at `speed` of a body of `mass`, in the
  !> summary (hertz_* keys), when the body is a generated round body (MESH
  !> SPHERE, SPHEROID or OUTLINE) of one material: E and nu are the
  !> material's instantaneous values (its elastic constants for an elastic
  !> material), R the mesh's radius of curvature at the contact pole
  !> (`pole_curvature_radius`: the sphere's radius on both grids, A^2/C for a
  !> spheroid; half the height is not, the contact grid's far pole being
  !> moved out to restore the volume). For a spheroid or an outline it is an
  !> estimate: Hertz's sphere of the pole's curvature with the body's mass.
  !> Left out, with the key hertz_reference saying why, when it would mean
  !> nothing: a PAD under the body; V not small against the bar wave speed sqrt(E/rho) (Hertz's
  !> theory is quasi-static; this also keeps V^2 from overflowing), a value
  !> that is not a finite number, a maximum approach alpha_m below the
  !> round-off of the node positions (geometry_tolerance R; V = 4.9e-324 m/s
  !> gives alpha_m = 0 and t_m = 0/V), or alpha_m not below R (Hertz's
  !> contact radius sqrt(R alpha_m) must be small against R).
  subroutine put_hertz_summary(deck, record, mass, speed)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: mass, speed
    type(hertz_t) :: hertz
    real(dp) :: radius, wave_speed
    if (.not. allocated(deck%mesh%source)) return
    if (deck%pad%line > 0) then
      call record_put(record, 'hertz_reference', 'none: the body lands on a PAD, not on the rigid plate (for a '// &
                      'thick pad, Hertz with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2: doc/method.md)')
      return
    end if
    if (.not. generated_round_body(deck%mesh) .or. size(deck%materials) /= 1) return
    if (speed == 0.0_dp) then
      call record_put(record, 'hertz_reference', 'none: the body touched the plate at rest (V = 0)')
      return
    end if
    radius = pole_curvature_radius(deck%mesh, deck%mesh%nelem)
    if (.not. (radius > 0.0_dp)) return
    associate (material => deck%materials(1))
    wave_speed = sqrt(material%young/max(material%density, tiny(1.0_dp)))
    if (.not. abs(speed) < wave_speed) then
      call record_put(record, 'hertz_reference', 'none: V = '//table_real(abs(speed))//' m/s is not small against the '// &
                      'wave speed sqrt(E/rho) = '//table_real(wave_speed)//' m/s (Hertz impact is quasi-static)')
      return
    end if
    hertz = hertz_impact(material%young, material%poisson, radius, mass, speed)
    if (.not. hertz_finite(hertz)) then
      call record_put(record, 'hertz_reference', 'none: not a finite number at V = '//table_real(abs(speed))//' m/s')
      return
    end if
    if (hertz%alpha_max <= geometry_tolerance*radius) then
      call record_put(record, 'hertz_reference', 'none: V = '//table_real(abs(speed))//' m/s is too small (alpha_m = '// &
                      table_real(hertz%alpha_max)//' m, below the round-off of the node positions)')
      return
    end if
    if (hertz%alpha_max >= radius) then
      call record_put(record, 'hertz_reference', 'none: alpha_m = '//table_real(hertz%alpha_max)//' m is not small '// &
                      'against R = '//table_real(radius)//' m')
      return
    end if
    call record_put_real(record, 'hertz_young_Pa', material%young)
    call record_put_real(record, 'hertz_poisson', material%poisson)
    end associate
    call record_put_real(record, 'hertz_radius_m', radius)
    call record_put_real(record, 'hertz_mass_kg', mass)
    call record_put_real(record, 'hertz_speed_m_s', abs(speed))
    call record_put_real(record, 'hertz_alpha_max_mm', 1.0e3_dp*hertz%alpha_max)
    call record_put_real(record, 'hertz_t_alpha_max_ms', 1.0e3_dp*hertz%t_alpha_max)
    call record_put_real(record, 'hertz_q_max_MPa', 1.0e-6_dp*hertz%q_max)
    call record_put_real(record, 'hertz_force_max_N', hertz%force_max)
    call record_put_real(record, 'hertz_contact_radius_mm', 1.0e3_dp*hertz%contact_radius)
    call record_put_real(record, 'hertz_contact_duration_ms', 1.0e3_dp*hertz%duration)
  end subroutine put_hertz_summary

  !> Every value of a Hertz reference, and its values in the summary's units, are finite numbers.
  pure logical function hertz_finite(hertz) result(finite)
    type(hertz_t), intent(in) :: hertz
    real(dp) :: values(6)
    values = [hertz%alpha_max, hertz%t_alpha_max, hertz%q_max, hertz%force_max, hertz%contact_radius, hertz%duration]
    finite = all(ieee_is_finite(values)) .and. all(ieee_is_finite(values*1.0e3_dp)) .and. &
             all(ieee_is_finite(values*1.0e-6_dp))
  end function hertz_finite
end module visco2d_hertz
