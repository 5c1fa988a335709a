!> Simulate only the effects a scene calls for. A full scene (a viscoelastic
!> sphere dropped with gravity onto a rigid plate) has the four effects
!> inertia, viscoelastic, contact and gravity; removing one card at a time
!> must turn off exactly that effect (in scene_effects, in the summary's
!> `effects` key, in listing.txt) and leave the others on, with the results
!> that must not depend on the removed effect unchanged:
!>   no PLATE    -> no contact keys, no contact history columns; the body
!>                  falls freely: v_cm = -V - g t, u_cm = -V t - g t^2/2,
!>                  gravity work = m g (V t + g t^2/2) (Wilson-theta is exact
!>                  for a constant acceleration);
!>   no GRAVITY  -> gravity_work_J = 0 exactly, the impact speed is V;
!>   no PRONY    -> history_values = 0 (nothing allocated), no dissipation
!>                  (the trapezoidal internal work of a linear elastic body is
!>                  its strain energy to round-off);
!>   STATIC      -> no dynamic keys; the plate carries the body's weight;
!>   no PLATE, no GRAVITY -> the body flies freely at its initial velocity
!>                  (exactly in the summary's digits; round-off in double).
program test_effects
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_scene, only: effects_t, scene_effects, effects_text
  use visco2d_driver, only: run_deck
  use visco2d_expect, only: summary_value
  use visco2d_record, only: record_t
  use visco2d_strings, only: message_real
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, &
                             history_index, history_last, read_lines
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/effects'
  character(*), parameter :: out_root = folder//'/out'
  real(dp), parameter :: speed = 1.0_dp          ! INITIAL VZ = -speed
  real(dp), parameter :: t_end = 2.0e-3_dp       ! TEND
  real(dp), parameter :: bulk = 13.5e6_dp, shear = 3.91e6_dp
  character(len=100), allocatable :: full(:)
  character(len=100) :: elastic_card
  character(len=*), parameter :: contact_keys(7) = [character(len=24) :: 'alpha_max_mm', 'contact_iterations', &
    'force_max_N', 'q_max_MPa', 'contact_radius_max_mm', 'contact_loss_J', 'stop_reason']
  character(len=*), parameter :: contact_columns(5) = [character(len=20) :: 't_ms', 'alpha_mm', 'force_N', &
    'q_MPa', 'n_contact']
  character(len=*), parameter :: dynamic_keys(5) = [character(len=16) :: 'theta', 'time_end_s', 'mass_kg', &
    'vz_cm_m_s', 'kinetic_J']
  type(record_t) :: r_full, r_noplate, r_nogravity, r_elastic, r_static, r_free
  type(deck_t) :: deck
  real(dp) :: g, young, poisson
  integer :: nelem

  call execute_command_line('rm -rf '//folder)
  call execute_command_line('mkdir -p '//out_root)

  full = [character(len=100) :: &
    'TITLE full scene: viscoelastic sphere dropped onto a plate', &  ! 1
    'ANALYSIS DYNAMIC', &                                            ! 2
    'GEOMETRY AXISYMMETRIC', &                                       ! 3
    'MATERIAL flesh VISCOELASTIC K=13.5e6 RHO=757', &                ! 4
    'PRONY G=3.91e6 BETA=203', &                                     ! 5
    'MESH SPHERE R=0.0381 LEVEL=1', &                                ! 6
    'INITIAL VZ=-1', &                                               ! 7
    'GRAVITY', &                                                     ! 8
    'PLATE Z=0', &                                                   ! 9
    'TIME DT=1e-5 TEND=2e-3', &                                      ! 10
    'END']                                                           ! 11
  ! The elastic material of the same instantaneous moduli: E = 9KG/(3K + G), nu = (3K - 2G)/(2(3K + G)).
  young = 9.0_dp*bulk*shear/(3.0_dp*bulk + shear)
  poisson = (3.0_dp*bulk - 2.0_dp*shear)/(2.0_dp*(3.0_dp*bulk + shear))
  write(elastic_card, '(a, es23.16, a, es23.16, a)') 'MATERIAL flesh ELASTIC E=', young, ' NU=', poisson, ' RHO=757'

  ! ------------------------------------------------------------ the full scene
  call scene('full', full, effects_t(inertia=.true., viscoelastic=.true., contact=.true., gravity=.true.), &
             'inertia viscoelastic contact gravity', r_full)
  g = deck%loads%gravity
  nelem = deck%mesh%nelem
  call contact_present('full', r_full)
  call check('full_gravity_work_positive', real_of(r_full, 'gravity_work_J') > 0.0_dp, &
             'gravity_work_J = '//summary_value(r_full, 'gravity_work_J'))
  ! One Prony term: 4 strain components x 4 Gauss points x nelem elements.
  call check('full_history_values', int_of(r_full, 'history_values') == 4*4*nelem*1, &
             'history_values = '//summary_value(r_full, 'history_values'))
  ! Memory dissipates: a fifth of the impact energy here (beta t ~ 0.4); elastic gives round-off (below).
  call check('full_dissipates', real_of(r_full, 'dissipated_J') > 0.01_dp*real_of(r_full, 'initial_kinetic_J'), &
             'dissipated_J = '//summary_value(r_full, 'dissipated_J'))

  ! ------------------------------------------------------------ no PLATE: no contact
  call scene('noplate', [full(1:8), full(10:11)], &
             effects_t(inertia=.true., viscoelastic=.true., contact=.false., gravity=.true.), &
             'inertia viscoelastic gravity', r_noplate)
  call contact_absent('noplate', r_noplate)
  call check('noplate_history_values', int_of(r_noplate, 'history_values') == 4*4*nelem, &
             'history_values = '//summary_value(r_noplate, 'history_values'))
  call check('noplate_runs_to_tend', int_of(r_noplate, 'steps') == 200, 'steps = '//summary_value(r_noplate, 'steps'))
  ! A uniform body force on a lumped mass gives a uniform acceleration -g: no strain,
  ! so the centre of mass falls as a point mass; Wilson-theta integrates constant
  ! acceleration exactly: round-off only (200 steps, rtol 1e-12).
  call check_close('noplate_vz_cm', history_last(r_noplate, 'vz_cm_m_s'), -speed - g*t_end, 1.0e-12_dp)
  call check_close('noplate_uz_cm', history_last(r_noplate, 'uz_cm_m'), -speed*t_end - 0.5_dp*g*t_end**2, 1.0e-12_dp)
  call check_close('noplate_gravity_work', history_last(r_noplate, 'gravity_work_J'), &
                   real_of(r_noplate, 'mass_kg')*g*(speed*t_end + 0.5_dp*g*t_end**2), 1.0e-9_dp)
  call check('noplate_no_strain', history_last(r_noplate, 'strain_J') <= &
             1.0e-12_dp*real_of(r_noplate, 'initial_kinetic_J'), &
             'strain_J = '//summary_value(r_noplate, 'strain_energy_J'))

  ! ------------------------------------------------------------ no GRAVITY
  call scene('nogravity', [full(1:7), full(9:11)], &
             effects_t(inertia=.true., viscoelastic=.true., contact=.true., gravity=.false.), &
             'inertia viscoelastic contact', r_nogravity)
  call check('nogravity_work_zero', history_last(r_nogravity, 'gravity_work_J') == 0.0_dp &
             .and. summary_value(r_nogravity, 'gravity_work_J') == '0', &
             'gravity_work_J = '//summary_value(r_nogravity, 'gravity_work_J'))
  call contact_present('nogravity', r_nogravity)
  call check('nogravity_history_values', int_of(r_nogravity, 'history_values') == 4*4*nelem, &
             'history_values = '//summary_value(r_nogravity, 'history_values'))
  ! The pole touches the plate at t = 0: the impact speed is V (10 digits in the summary).
  call check_close('nogravity_impact_speed', real_of(r_nogravity, 'impact_velocity_m_s'), speed, 1.0e-9_dp)
  ! The body's weight adds to the impact: gravity on goes deeper.
  call check('gravity_deepens_impact', real_of(r_full, 'alpha_max_mm') > real_of(r_nogravity, 'alpha_max_mm'), &
             'alpha_max_mm with gravity '//summary_value(r_full, 'alpha_max_mm')//', without '// &
             summary_value(r_nogravity, 'alpha_max_mm'))

  ! ------------------------------------------------------------ no PRONY: elastic
  call scene('elastic', [full(1:3), elastic_card, full(6:11)], &
             effects_t(inertia=.true., viscoelastic=.false., contact=.true., gravity=.true.), &
             'inertia contact gravity', r_elastic)
  call check('elastic_history_values_zero', summary_value(r_elastic, 'history_values') == '0', &
             'history_values = '//summary_value(r_elastic, 'history_values'))
  call contact_present('elastic', r_elastic)
  call check('elastic_gravity_work_positive', real_of(r_elastic, 'gravity_work_J') > 0.0_dp)
  ! Linear elastic: the trapezoidal internal work is exactly 1/2 u.K u, so nothing
  ! is dissipated but round-off (1e-9 of the impact energy is ~1e5 times round-off).
  call check('elastic_no_dissipation', abs(real_of(r_elastic, 'dissipated_J')) <= &
             1.0e-9_dp*real_of(r_elastic, 'initial_kinetic_J'), 'dissipated_J = '//summary_value(r_elastic, 'dissipated_J'))
  ! Same instantaneous moduli (the Hertz reference uses them), and G(t) <= G(0):
  ! the relaxing body is softer and goes deeper.
  call check_close('elastic_same_instantaneous_young', real_of(r_elastic, 'hertz_young_Pa'), &
                   real_of(r_full, 'hertz_young_Pa'), 1.0e-9_dp)
  call check('relaxation_deepens_impact', real_of(r_full, 'alpha_max_mm') > real_of(r_elastic, 'alpha_max_mm'), &
             'alpha_max_mm viscoelastic '//summary_value(r_full, 'alpha_max_mm')//', elastic '// &
             summary_value(r_elastic, 'alpha_max_mm'))

  ! ------------------------------------------------------------ STATIC: no inertia
  ! (STATIC with memory is rejected by design -- PRONY terms relax in time -- so elastic.)
  block
    type(error_t), allocatable :: error
    call write_deck(folder//'/static_memory.inp', [full(1), 'ANALYSIS STATIC', full(3:6), full(8:9), full(11)])
    call read_deck(folder//'/static_memory.inp', deck, error)
    call check('static_memory_rejected', allocated(error), 'STATIC with PRONY BETA > 0 was accepted')
    if (allocated(error)) call check_text_contains('static_memory_message', error_text(error), 'QUASISTATIC')
  end block
  call scene('static', [full(1), 'ANALYSIS STATIC', full(3:3), elastic_card, full(6:6), 'GRAVITY G=1000', &
             full(9:9), full(11:11)], effects_t(inertia=.false., viscoelastic=.false., contact=.true., gravity=.true.), &
             'contact gravity', r_static)
  call check('static_one_step', summary_value(r_static, 'steps') == '1', 'steps = '//summary_value(r_static, 'steps'))
  call check('static_factorizations', len(summary_value(r_static, 'factorizations')) > 0)
  call check('static_contact_iterations', len(summary_value(r_static, 'contact_iterations')) > 0)
  call check('static_force_key', len(summary_value(r_static, 'force_N')) > 0)
  call check('static_alpha_key', len(summary_value(r_static, 'alpha_mm')) > 0)
  call check('static_no_history_values', len(summary_value(r_static, 'history_values')) == 0, &
             'history_values = '//summary_value(r_static, 'history_values'))
  call keys_absent('static', r_static, dynamic_keys)
  call check('static_no_kinetic_column', history_index(r_static, 'kinetic_J') == 0 &
             .and. history_index(r_static, 'vz_cm_m_s') == 0)
  ! Equilibrium: the plate carries the whole weight M G (M from the dynamic run of
  ! the same mesh and density; 10 digits in the summary).
  call check_close('static_plate_carries_weight', real_of(r_static, 'force_N'), &
                   1000.0_dp*real_of(r_elastic, 'body_mass_kg'), 1.0e-8_dp)

  ! ------------------------------------------------------------ no PLATE, no GRAVITY: free flight
  call scene('free', [full(1:7), full(10:11)], &
             effects_t(inertia=.true., viscoelastic=.true., contact=.false., gravity=.false.), &
             'inertia viscoelastic', r_free)
  call contact_absent('free', r_free)
  ! Exactly V in the summary's 10 digits. In double precision a rigid translation
  ! is carried through the Wilson-theta solve with round-off only: the step
  ! recovers a = 6/tau^2 (du - tau v) - ... from a du correct to ~eps, so
  ! |a| <~ 6 eps V/(theta dt) and |v + V| <~ 6 eps V t_end/(theta dt) = 1.9e-13 m/s.
  call check('free_vz_cm_summary_exact', summary_value(r_free, 'vz_cm_m_s') == '-1.000000000E+000', &
             'vz_cm_m_s = '//summary_value(r_free, 'vz_cm_m_s'))
  call check_close('free_vz_cm_roundoff', history_last(r_free, 'vz_cm_m_s'), -speed, &
                   0.0_dp, 6.0_dp*epsilon(1.0_dp)*speed*t_end/(1.4_dp*1.0e-5_dp))
  call check_close('free_uz_cm', history_last(r_free, 'uz_cm_m'), -speed*t_end, 1.0e-12_dp)
  call check('free_gravity_work_zero', history_last(r_free, 'gravity_work_J') == 0.0_dp)

  call print_table()
  call test_summary('test_effects')

contains

  !> Write and read a variant; check its effects (scene_effects, effects_text);
  !> run it; check the summary's effects key and the listing's effects line.
  subroutine scene(name, deck_lines, expected, text, record)
    character(*), intent(in) :: name, text
    character(*), intent(in) :: deck_lines(:)
    type(effects_t), intent(in) :: expected
    type(record_t), intent(out) :: record
    type(effects_t) :: effects
    type(error_t), allocatable :: error
    character(:), allocatable :: path
    path = folder//'/'//name//'.inp'
    call write_deck(path, deck_lines)
    call read_deck(path, deck, error)
    call check(name//'_reads', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    effects = scene_effects(deck)
    call check(name//'_inertia', effects%inertia .eqv. expected%inertia)
    call check(name//'_viscoelastic', effects%viscoelastic .eqv. expected%viscoelastic)
    call check(name//'_contact', effects%contact .eqv. expected%contact)
    call check(name//'_gravity', effects%gravity .eqv. expected%gravity)
    call check(name//'_effects_text', effects_text(effects) == text, 'effects_text "'//effects_text(effects)//'"')
    call run_deck(path, out_root, record, error)
    call check(name//'_runs', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    call check(name//'_summary_effects', summary_value(record, 'effects') == text, &
               'effects = "'//summary_value(record, 'effects')//'"')
    call check(name//'_listing_effects', listing_effects(out_root//'/'//name//'/listing.txt') == text, &
               'listing.txt effects "'//listing_effects(out_root//'/'//name//'/listing.txt')//'"')
  end subroutine scene

  !> The value of the `effects` line of a listing ('' if absent).
  function listing_effects(path) result(text)
    character(*), intent(in) :: path
    character(:), allocatable :: text, lines(:), line
    logical :: found
    integer :: k
    text = ''
    call read_lines(path, lines, found)
    do k = 1, size(lines)
      line = adjustl(lines(k))
      if (index(line, 'effects ') == 1) then
        text = trim(adjustl(line(9:)))
        exit
      end if
    end do
  end function listing_effects

  subroutine contact_present(name, record)
    character(*), intent(in) :: name
    type(record_t), intent(in) :: record
    integer :: k
    do k = 1, size(contact_keys)
      call check(name//'_has_'//trim(contact_keys(k)), len(summary_value(record, trim(contact_keys(k)))) > 0)
    end do
    do k = 1, size(contact_columns)
      call check(name//'_has_column_'//trim(contact_columns(k)), history_index(record, trim(contact_columns(k))) > 0)
    end do
    call check(name//'_stop_reason', summary_value(record, 'stop_reason') == 'maximum deformation', &
               'stop_reason = '//summary_value(record, 'stop_reason'))
  end subroutine contact_present

  subroutine contact_absent(name, record)
    character(*), intent(in) :: name
    type(record_t), intent(in) :: record
    integer :: k
    call keys_absent(name, record, contact_keys)
    call keys_absent(name, record, [character(len=24) :: 'hertz_alpha_max_mm', 'plate_z_m'])
    do k = 1, size(contact_columns)
      call check(name//'_no_column_'//trim(contact_columns(k)), history_index(record, trim(contact_columns(k))) == 0)
    end do
  end subroutine contact_absent

  subroutine keys_absent(name, record, keys)
    character(*), intent(in) :: name
    type(record_t), intent(in) :: record
    character(*), intent(in) :: keys(:)
    integer :: k
    do k = 1, size(keys)
      call check(name//'_no_'//trim(keys(k)), len(summary_value(record, trim(keys(k)))) == 0, &
                 trim(keys(k))//' = '//summary_value(record, trim(keys(k))))
    end do
  end subroutine keys_absent

  real(dp) function real_of(record, key) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    character(:), allocatable :: text
    integer :: ios
    value = huge(1.0_dp)
    text = summary_value(record, key)
    read(text, *, iostat=ios) value
    if (ios /= 0) value = huge(1.0_dp)
  end function real_of

  integer function int_of(record, key) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    character(:), allocatable :: text
    integer :: ios
    value = -huge(1)
    text = summary_value(record, key)
    read(text, *, iostat=ios) value
    if (ios /= 0) value = -huge(1)
  end function int_of

  subroutine print_table()
    print '(a)', ''
    print '(a)', '| scene | effects | history_values | gravity_work_J | alpha_max_mm | vz_cm_m_s (end) | steps |'
    print '(a)', '|---|---|---|---|---|---|---|'
    call row('full', r_full)
    call row('no PLATE', r_noplate)
    call row('no GRAVITY', r_nogravity)
    call row('ELASTIC (no PRONY)', r_elastic)
    call row('no PLATE, no GRAVITY', r_free)
    print '(a)', '| STATIC, G=1000 (force_N '//summary_value(r_static, 'force_N')//', alpha_mm '// &
      summary_value(r_static, 'alpha_mm')//') | '//summary_value(r_static, 'effects')//' | - | - | - | - | '// &
      summary_value(r_static, 'steps')//' |'
    print '(a)', ''
  end subroutine print_table

  subroutine row(label, record)
    character(*), intent(in) :: label
    type(record_t), intent(in) :: record
    character(:), allocatable :: alpha
    alpha = summary_value(record, 'alpha_max_mm')
    if (len(alpha) == 0) alpha = '-'
    print '(a)', '| '//label//' | '//summary_value(record, 'effects')//' | '// &
      summary_value(record, 'history_values')//' | '//summary_value(record, 'gravity_work_J')//' | '//alpha// &
      ' | '//summary_value(record, 'vz_cm_m_s')//' | '//summary_value(record, 'steps')//' |'
  end subroutine row
end program test_effects
