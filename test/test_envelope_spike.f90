!> The bruise envelopes of an impact carry no false peak at first contact:
!> the maximum-shear envelope converges with the mesh level and the time
!> step to Hertz's subsurface maximum, and no bruise is reported above it.
!>
!> The deck: the Table-1 sphere (E = 18.11 MPa, nu = 0.219, rho = 756.85
!> kg/m^3, R = 36.6 mm) at 2 m/s on the rigid plate, frictionless (SLIP:
!> Hertz's contact), Wilson-theta 1.4 (the default), to maximum
!> deformation, MESH SPHERE LEVEL = 2..5, DT = 0.01, 0.02, 0.04 ms, with
!> BRUISE CRITERION=MAXSHEAR STRESS=1 MPa.
!>
!> The reference: Hertz's maximum of (sigma_1 - sigma_3)/2 on the axis, from
!> the closed-form axis stresses (Johnson, Contact Mechanics, eq. 3.45),
!>   sigma_z/p0 = -1/(1 + zeta^2),
!>   sigma_r/p0 = sigma_theta/p0 = -(1 + nu)(1 - zeta atan(1/zeta)) + 1/(2(1 + zeta^2)),
!> zeta = z/a, maximized here over zeta for the deck's nu (0.3291 p0 at
!> zeta = 0.4541 for nu = 0.219), with p0 = 3 F/(2 pi a^2) from Hertz's
!> impact solution (the summary's hertz_force_max_N and
!> hertz_contact_radius_mm: F = 406.1 N, a = 8.369 mm, p0 = 2.769 MPa,
!> tau_max = 0.9112 MPa). The envelope's max_shear is the same measure: the
!> three principal stresses, sigma_theta one of them.
!>
!> Before the fix the envelope took the state at t + dt, where Wilson-theta
!> answers the velocity that the free neighbours of a node arrested on the
!> plate keep with a displacement (1 - 1/theta^2) v dt in the stiff modes of
!> the pole elements: a maximum at the first step growing with dt and 1/h
!> (measured: 1.39 MPa at level 3, 0.04 ms; 2.71 MPa at level 4, 0.04 ms;
!> 1.39, 2.70, 5.34 MPa at level 5, 0.01, 0.02, 0.04 ms) and a false 1 MPa
!> bruise (0.0016 cm^3 at level 3, 0.04 ms; 0.0026 cm^3 at level 4, 0.04
!> ms). Now it takes the state at the solve point t + theta dt, where the
!> integrator holds equilibrium, as the plate reactions. Measured after:
!>   level 2: 0.9081, 0.9065, 0.9006 MPa (dt 0.01, 0.02, 0.04 ms)
!>   level 3: 0.8961, 0.8958, 0.8961
!>   level 4: 0.8927, 0.8927, 0.8931
!>   level 5: 0.8914, 0.8916, 0.8917   (-2.2 % from Hertz)
!> at 1.21-1.30 ms, 4.5-4.8 mm under the undeformed pole.
!>
!> Checks and tolerances:
!> 1. Every run's maximum within 5 % of Hertz's: the finite sphere is not
!>    Hertz's half-space (a/R = 0.23 at maximum compression; the same 5 % as
!>    test_bruise's static Hertz check, whose measured offsets are -2 to
!>    -3 %); measured -0.3 to -2.2 %. Before the fix 6 of the 12 runs fail
!>    it (by +52 % to +486 %).
!> 2. Converging with the time step: at each level the three DT agree
!>    within 1 % (measured spread 0.84 % at level 2, <= 0.05 % at levels 3-5;
!>    before: a factor 2-4).
!> 3. Converging with the level: at DT = 0.01 ms the change from level 4 to
!>    5 is under 0.5 % (measured 0.15 %; levels 2-3 1.3 %, 3-4 0.38 %) and
!>    smaller than that from level 2 to 3.
!> 4. The maximum is where and when Hertz's is: after half of Hertz's time
!>    to maximum deformation (1.408 ms; before the fix it was the first
!>    step, 0.01-0.04 ms) and at a depth of 0.5-1.5 times Hertz's 0.454 a =
!>    3.80 mm (the key is measured in the undeformed body, below the
!>    undeformed pole, which the compression of the material above the
!>    point shifts by a fraction of alpha = 1.8 mm; before: 0.09 mm, the
!>    pole element).
!> 5. No bruise at 1 MPa: every Gauss point's envelope stays below Hertz's
!>    maximum, under the threshold (bruise_volume_cm3 = 0, exactly).
program test_envelope_spike
  use visco2d_kinds, only: dp, pi
  use visco2d_error, only: error_t
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_close, test_summary, write_deck, summary_real, message_of
  use visco2d_test_decks, only: deck_line_length
  use visco2d_analytic, only: hertz_axis_maximum
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_envelope_spike'
  character(*), parameter :: dt_text(3) = ['1e-5', '2e-5', '4e-5']
  real(dp), parameter :: nu = 0.219_dp
  real(dp) :: maximum(2:5, 3), reference, p0, zeta_max, tau_ratio, t_hertz, depth_hertz
  integer :: level, k

  call execute_command_line('mkdir -p '//folder)
  call hertz_axis_maximum(nu, tau_ratio, zeta_max)
  do level = 2, 5
    do k = 1, 3
      call one_run(level, k)
    end do
    call check('spike_level_'//integer_text(level)//'_dt_spread_within_1pc', &
               maxval(maximum(level, :)) - minval(maximum(level, :)) <= 0.01_dp*reference, &
               'envelope maxima over DT 0.01, 0.02, 0.04 ms: '//real_list(maximum(level, :)))
  end do
  call check('spike_level_4_to_5_within_half_pc', abs(maximum(5, 1) - maximum(4, 1)) <= 0.005_dp*reference, &
             'levels 4, 5 at DT 0.01 ms: '//real_list(maximum(4:5, 1)))
  call check('spike_level_changes_shrink', abs(maximum(5, 1) - maximum(4, 1)) < abs(maximum(3, 1) - maximum(2, 1)), &
             'levels 2-5 at DT 0.01 ms: '//real_list(maximum(:, 1)))
  call test_summary('test_envelope_spike')

contains

  !> One impact; its envelope maximum into maximum(level, k) and its own checks.
  subroutine one_run(level, k)
    integer, intent(in) :: level, k
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: name
    real(dp) :: force, radius, value
    name = 'l'//integer_text(level)//'_dt'//dt_text(k)
    call write_deck(folder//'/'//name//'.inp', [character(len=deck_line_length) :: &
      'TITLE Table 1 sphere at 2 m/s, frictionless', 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL='//integer_text(level), &
      'INITIAL VZ=-2', 'TIME DT='//dt_text(k)//' TEND=4e-3', 'PLATE Z=0 SLIP', 'STOP AT=MAXDEFORMATION', &
      'OUTPUT EVERY=1000', 'BRUISE CRITERION=MAXSHEAR STRESS=1e6', 'END'])
    call run_deck(folder//'/'//name//'.inp', folder//'/out', record, error)
    call check('spike_'//name//'_runs', .not. allocated(error), message_of(error))
    if (allocated(error)) then
      maximum(level, k) = 0.0_dp
      return
    end if
    force = summary_real(record, 'hertz_force_max_N')
    radius = 1.0e-3_dp*summary_real(record, 'hertz_contact_radius_mm')
    p0 = 3.0_dp*force/(2.0_dp*pi*radius**2)
    reference = tau_ratio*p0
    t_hertz = 1.0e-3_dp*summary_real(record, 'hertz_t_alpha_max_ms')
    depth_hertz = 1.0e3_dp*zeta_max*radius
    if (level == 2 .and. k == 1) print '(a, f8.5, a, f7.4, a, es12.5, a, f7.4, a)', '# Hertz: tau_max = ', tau_ratio, &
      ' p0 at zeta = ', zeta_max, ', p0 = ', p0, ' Pa, depth ', depth_hertz, ' mm'
    value = summary_real(record, 'envelope_max_shear_max_Pa')
    maximum(level, k) = value
    print '(a, i0, 3a, es12.5, a, f7.3, a, f7.3, a, f7.4, a)', '# level ', level, ', DT ', dt_text(k), ': ', value, &
      ' Pa (', 100.0_dp*(value/reference - 1.0_dp), ' %), depth ', summary_real(record, 'envelope_max_shear_depth_mm'), &
      ' mm, t ', 1.0e3_dp*summary_real(record, 'envelope_max_shear_time_s'), ' ms'
    call check_close('spike_'//name//'_max_shear_is_hertz', value, reference, 0.05_dp)
    call check('spike_'//name//'_max_after_half_hertz_time', &
               summary_real(record, 'envelope_max_shear_time_s') > 0.5_dp*t_hertz, &
               'envelope maximum at '//real_list([summary_real(record, 'envelope_max_shear_time_s')])//' s')
    associate (depth => summary_real(record, 'envelope_max_shear_depth_mm'))
    call check('spike_'//name//'_max_at_hertz_depth', depth > 0.5_dp*depth_hertz .and. depth < 1.5_dp*depth_hertz, &
               'depth '//real_list([depth])//' mm against Hertz '//real_list([depth_hertz]))
    end associate
    call check_close('spike_'//name//'_no_bruise_at_1MPa', summary_real(record, 'bruise_volume_cm3'), 0.0_dp, 0.0_dp, &
                     atol=0.0_dp)
  end subroutine one_run

  function real_list(values) result(text)
    real(dp), intent(in) :: values(:)
    character(:), allocatable :: text
    character(len=24) :: buffer
    integer :: i
    text = ''
    do i = 1, size(values)
      write(buffer, '(es12.5)') values(i)
      text = text//trim(adjustl(buffer))
      if (i < size(values)) text = text//', '
    end do
  end function real_list

end program test_envelope_spike
