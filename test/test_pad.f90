!> Verification of the cushioned plate (PAD card: src/cards/visco2d_pad_mesh.f90,
!> the node-to-segment contact of src/contact/visco2d_contact.f90 and
!> visco2d_capacitance.f90) on the elastic sphere of Table 1 (E 18.11 MPa,
!> nu 0.219, rho 756.85, R 36.6 mm, V 0.9982 m/s, g 9.8), level 1, DT 0.01 ms:
!>
!>  1. A pad 1000 times stiffer than the fruit gives the rigid-plate answer:
!>     alpha_m and q_m within 0.5 % (the pad then compresses by ~1/1000 of
!>     alpha: its own compliance is the only difference, well under 0.5 %).
!>  2. Pads of decreasing stiffness (E_pad/E = 10, 1, 0.3, 0.1; 10 mm, SLIP,
!>     RELEASE=YES, to separation): q_m falls and the contact lasts longer,
!>     strictly, at every step down; alpha (the fruit's own deformation,
!>     the approach less the pad's compression) falls too.
!>  2b. Equal and opposite: the impulse of the contact force on the fruit,
!>     the time integral of force_N (trapezoidal over every step), equals the
!>     fruit's change of momentum M (V_in + V_out) plus the weight's impulse
!>     M g t_c over the contact, to 1 % (measured within 0.1 %): the force
!>     booked on the fruit is the force that stops and returns it.
!>  3. Energy: the books close on every run (kinetic + strain energy of
!>     fruit and pad + contact loss = initial kinetic energy + gravity work):
!>     balance_error_max_rel below 2 % (the rigid plate's own is ~0.1 %; a
!>     node landing on the moving surface is booked as the pair's inelastic
!>     collision, with their reduced mass, an estimate).
!>  4. Hertz with the combined modulus 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2:
!>     on a thick, wide pad of the fruit's own material at V = 0.2 m/s
!>     (a/R ~ 0.1), the largest total approach (alpha + pad compression)
!>     over Hertz's alpha_m with E*, against the same ratio for the rigid
!>     plate with E/(1 - nu^2): the pad's ratio follows the rigid plate's
!>     to 3 % (the pad is a layer R thick, ~13 contact radii, on a frictionless
!>     base, not a half-space; its mesh grows by 1.2 with depth: measured
!>     +1.7 %). With equal materials Hertz splits the approach equally: the
!>     fruit's alpha and the pad's compression agree to 3 % (measured 0.5 %).
!>  4b. A thin pad on a thick one (COVER=, COVERMAT=): a 1 mm cover of the
!>     pad's own material gives the plain pad's alpha, q and F within 2 %
!>     (only the rows' spacing differs: measured within 0.1 %); a stiff
!>     cover (a 50 MPa belt on a 5.4 MPa foam) spreads the load: q lower.
!>  5. STATIC: the sphere (level 2) pressed onto the plate by its top node
!>     (FIX TOP Z UZ=-0.5 mm): a pad 1000 times stiffer gives the rigid
!>     plate's force and alpha within 0.5 % (measured 0.05 %); a pad of the
!>     fruit's flesh takes a smaller force at the same travel. Pressed by
!>     gravity alone (resting on the pad, level 3), on a pad of its own flesh
!>     36.6 mm thick: the pad carries the weight (to round-off), the total
!>     approach over Hertz's with 1/E* = sum (1 - nu^2)/E follows the rigid
!>     plate's ratio over Hertz with E/(1 - nu^2) -- both tend to 1 as
!>     a/R -> 0 -- to 1 % at a/R = 0.045 and 2 % at 0.097 (measured 0.06 %
!>     and 1.5 %: the layer's finite thickness shows as a grows), and the
!>     fruit and the pad share the approach to 1 % (measured 0.3 %, 0.5 %).
!>  6. No PAD without a PLATE; an unknown MAT=.
!> Every number is printed in markdown tables. Decks are written to
!> build/test-tmp/test_pad/.
program test_pad
  use visco2d_kinds, only: dp, pi
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_static_contact, only: solve_static_contact
  use visco2d_hertz, only: hertz_t, hertz_impact
  use visco2d_record, only: record_t
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, history_column, &
                             summary_real, message_of
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_pad'
  integer, parameter :: line_length = 100
  real(dp), parameter :: young = 18.11e6_dp, poisson = 0.219_dp, density = 756.85_dp, radius = 0.0366_dp
  character(*), parameter :: fruit = 'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85'

  type :: run_t
    character(:), allocatable :: name
    type(record_t) :: record
    logical :: ok = .false.
  end type run_t

  call execute_command_line('mkdir -p '//folder)
  call stiff_pad()
  call softer_pads()
  call hertz_combined()
  call covered_pads()
  call static_pads()
  call bad_pads()
  call test_summary('test_pad')

contains

  !> The deck lines of the Table 1 sphere at `speed` with `plate`, `stop`, and a pad card ('' for none).
  function impact_lines(level, speed, plate, stop_card, pad_material, pad) result(lines)
    character(*), intent(in) :: level, speed, plate, stop_card, pad_material, pad
    character(len=line_length), allocatable :: lines(:)
    integer :: count
    count = 10
    if (len(pad) > 0) count = 12
    allocate(lines(count))
    lines(1:10) = [character(len=line_length) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', fruit, &
                   'MESH SPHERE R=0.0366 LEVEL='//level//' MAT=apple', 'INITIAL VZ=-'//speed//' AZ=-9.8', &
                   'GRAVITY G=9.8', 'WILSON THETA=1.4', 'TIME DT=1e-5 TEND=40e-3', plate, stop_card]
    if (len(pad) > 0) lines(11:12) = [character(len=line_length) :: pad_material, pad]
  end function impact_lines

  !> Write TITLE + body + END, read and run it (a failed check if it does not run).
  function run_case(name, body) result(run)
    character(*), intent(in) :: name
    character(len=line_length), intent(in) :: body(:)
    type(run_t) :: run
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    run%name = name
    call read_deck(deck_file(name, body), deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, run%record, error)
    if (allocated(error)) then
      call check('run_'//name, .false., error_text(error))
      return
    end if
    run%ok = .true.
  end function run_case

  !> Write TITLE + body + END to the test folder; the file's path.
  function deck_file(name, body) result(path)
    character(*), intent(in) :: name
    character(len=line_length), intent(in) :: body(:)
    character(:), allocatable :: path
    character(len=line_length), allocatable :: deck_lines(:)
    path = folder//'/'//name//'.inp'
    allocate(deck_lines(size(body) + 2))
    deck_lines(1) = 'TITLE '//name
    deck_lines(2:size(body) + 1) = body
    deck_lines(size(body) + 2) = 'END'
    call write_deck(path, deck_lines)
  end function deck_file

  !> A real summary value of a run (NaN, and a failed check, if absent).
  real(dp) function value_of(run, key) result(x)
    type(run_t), intent(in) :: run
    character(*), intent(in) :: key
    x = summary_real(run%record, key)
  end function value_of

  !> A number in fixed notation with `digits` decimals.
  function fx(x, digits) result(text)
    real(dp), intent(in) :: x
    integer, intent(in) :: digits
    character(:), allocatable :: text
    character(len=32) :: buffer
    character(len=12) :: form
    write(form, '(a,i0,a)') '(f0.', digits, ')'
    write(buffer, form) x
    text = trim(buffer)
  end function fx

  !> 1. A pad 1000 times stiffer than the fruit against the rigid plate.
  subroutine stiff_pad()
    type(run_t) :: rigid, pad
    real(dp) :: alpha_error, q_error
    rigid = run_case('rigid_stick', impact_lines('1', '0.9982', 'PLATE Z=0 STICK', 'STOP AT=MAXDEFORMATION', '', ''))
    pad = run_case('stiff_pad_stick', impact_lines('1', '0.9982', 'PLATE Z=0 STICK', 'STOP AT=MAXDEFORMATION', &
                   'MATERIAL stiff ELASTIC E=18.11e9 NU=0.3 RHO=1000', 'PAD THICKNESS=0.01 MAT=stiff'))
    if (.not. (rigid%ok .and. pad%ok)) return
    alpha_error = value_of(pad, 'alpha_max_mm')/value_of(rigid, 'alpha_max_mm') - 1.0_dp
    q_error = value_of(pad, 'q_max_MPa')/value_of(rigid, 'q_max_MPa') - 1.0_dp
    print '(a)', '| Table 1, level 1 | alpha_m (mm) | q_m (MPa) | F_m (N) | pad compression (mm) |'
    print '(a)', '|---|---|---|---|---|'
    print '(a)', '| rigid plate | '//fx(value_of(rigid, 'alpha_max_mm'), 4)//' | '// &
      fx(value_of(rigid, 'q_max_MPa'), 4)//' | '//fx(value_of(rigid, 'force_max_N'), 2)//' | - |'
    print '(a)', '| pad E = 1000 E_fruit, 10 mm | '//fx(value_of(pad, 'alpha_max_mm'), 4)//' | '// &
      fx(value_of(pad, 'q_max_MPa'), 4)//' | '//fx(value_of(pad, 'force_max_N'), 2)//' | '// &
      fx(value_of(pad, 'pad_compression_max_mm'), 5)//' |'
    call check('stiff pad: alpha_m within 0.5 % of the rigid plate ('//fx(100*alpha_error, 3)//' %)', &
               abs(alpha_error) <= 5.0e-3_dp)
    call check('stiff pad: q_m within 0.5 % of the rigid plate ('//fx(100*q_error, 3)//' %)', abs(q_error) <= 5.0e-3_dp)
    call check('stiff pad: compresses by less than 1/100 of alpha', &
               value_of(pad, 'pad_compression_max_mm') < 0.01_dp*value_of(pad, 'alpha_max_mm'))
  end subroutine stiff_pad

  !> 2.-3. Pads of decreasing stiffness, to separation.
  subroutine softer_pads()
    character(len=8), parameter :: moduli(4) = [character(len=8) :: '181.1e6', '18.11e6', '5.433e6', '1.811e6']
    real(dp), parameter :: ratios(4) = [10.0_dp, 1.0_dp, 0.3_dp, 0.1_dp]
    type(run_t) :: runs(0:4)
    real(dp) :: q(0:4), duration(0:4), alpha(0:4), balance(0:4)
    integer :: k
    character(len=24) :: label
    runs(0) = run_case('rigid_separation', impact_lines('1', '0.9982', 'PLATE Z=0 SLIP RELEASE=YES', &
                       'STOP AT=SEPARATION', '', ''))
    do k = 1, 4
      runs(k) = run_case('pad_'//trim(moduli(k)), impact_lines('1', '0.9982', 'PLATE Z=0 SLIP RELEASE=YES', &
                         'STOP AT=SEPARATION', 'MATERIAL foam ELASTIC E='//trim(moduli(k))//' NU=0.3 RHO=100', &
                         'PAD THICKNESS=0.01 MAT=foam'))
    end do
    if (.not. all(runs%ok)) return
    print '(a)', ''
    print '(a)', '| plate | alpha_m (mm) | q_m (MPa) | F_m (N) | contact (ms) | pad compression (mm) | restitution | '// &
                 'balance error (rel.) |'
    print '(a)', '|---|---|---|---|---|---|---|---|'
    do k = 0, 4
      alpha(k) = value_of(runs(k), 'alpha_max_mm')
      q(k) = value_of(runs(k), 'q_max_MPa')
      duration(k) = value_of(runs(k), 'contact_duration_ms')
      balance(k) = value_of(runs(k), 'balance_error_max_rel')
      if (k == 0) then
        label = 'rigid'
      else
        write(label, '(a,f0.1,a)') 'pad E = ', ratios(k), ' E_fruit'
      end if
      print '(a)', '| '//trim(label)//' | '//fx(alpha(k), 4)//' | '//fx(q(k), 4)//' | '// &
        fx(value_of(runs(k), 'force_max_N'), 2)//' | '//fx(duration(k), 3)//' | '// &
        compression_text(runs(k), k > 0)//' | '// &
        fx(value_of(runs(k), 'coefficient_of_restitution'), 4)//' | '//fx(balance(k), 5)//' |'
    end do
    do k = 1, 4
      call check('softer pad '//char(48 + k)//': q_m falls', q(k) < q(k - 1))
      call check('softer pad '//char(48 + k)//': the contact lasts longer', duration(k) > duration(k - 1))
      call check('softer pad '//char(48 + k)//': the fruit deforms less', alpha(k) < alpha(k - 1))
    end do
    do k = 0, 4
      call check('energy books close ('//runs(k)%name//', '//fx(100*balance(k), 3)//' %)', abs(balance(k)) < 0.02_dp)
    end do
    do k = 0, 4
      call check_impulse(runs(k))
    end do
    call check('the softest pad''s large strain is reported at its PAD card', any_warning(runs(4)%record, &
               ': PAD: the largest principal strain in the pad'))
  end subroutine softer_pads

  !> True if a run warning of the record contains `fragment`.
  logical function any_warning(record, fragment)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: fragment
    integer :: k
    any_warning = .false.
    if (.not. allocated(record%warnings)) return
    do k = 1, size(record%warnings)
      if (index(record%warnings(k)%text, fragment) > 0) any_warning = .true.
    end do
  end function any_warning

  !> The impulse of force_N over the run against the fruit's momentum change and its weight's impulse.
  subroutine check_impulse(run)
    type(run_t), intent(in) :: run
    real(dp), allocatable :: t(:), force(:)
    real(dp) :: impulse, momentum, mass
    t = history_column(run%record, 't_s')
    force = history_column(run%record, 'force_N')
    if (size(t) < 2 .or. size(force) /= size(t)) return
    impulse = sum(0.5_dp*(force(2:) + force(:size(t) - 1))*(t(2:) - t(:size(t) - 1)))
    mass = value_of(run, 'mass_kg')
    momentum = mass*(value_of(run, 'impact_velocity_m_s') + value_of(run, 'rebound_velocity_m_s')) + &
               mass*9.8_dp*1.0e-3_dp*value_of(run, 'contact_duration_ms')
    print '(a)', run%name//': impulse '//fx(impulse*1.0e3_dp, 4)//' mN s, momentum change + weight '// &
      fx(momentum*1.0e3_dp, 4)//' mN s'
    call check_close('impulse of the contact force = momentum change ('//run%name//', 1 %)', impulse, momentum, 0.01_dp)
  end subroutine check_impulse

  !> The pad's compression of a run, or '-' for the rigid plate.
  function compression_text(run, pad) result(text)
    type(run_t), intent(in) :: run
    logical, intent(in) :: pad
    character(:), allocatable :: text
    text = '-'
    if (pad) text = fx(value_of(run, 'pad_compression_max_mm'), 4)
  end function compression_text

  !> 4. Hertz with the combined modulus on a thick pad of the fruit's material.
  subroutine hertz_combined()
    type(run_t) :: rigid, pad
    type(hertz_t) :: hertz_rigid, hertz_pad
    real(dp), allocatable :: alpha(:), compression(:)
    real(dp) :: mass, combined, ratio_rigid, ratio_pad
    rigid = run_case('hertz_rigid', impact_lines('2', '0.2', 'PLATE Z=0 SLIP', 'STOP AT=MAXDEFORMATION', '', ''))
    pad = run_case('hertz_pad', impact_lines('2', '0.2', 'PLATE Z=0 SLIP', 'STOP AT=MAXDEFORMATION', &
                   'MATERIAL flesh ELASTIC E=18.11e6 NU=0.219 RHO=756.85', &
                   'PAD THICKNESS=0.0366 WIDTH=0.1 MAT=flesh BOTTOM=SLIP'))
    if (.not. (rigid%ok .and. pad%ok)) return
    mass = value_of(rigid, 'mass_kg')
    hertz_rigid = hertz_impact(young, poisson, radius, mass, 0.2_dp)
    combined = 1.0_dp/(2.0_dp*(1.0_dp - poisson**2)/young)           ! E* with E2 = E1
    hertz_pad = hertz_impact(combined, 0.0_dp, radius, mass, 0.2_dp)   ! E*/(1 - 0^2) = E*
    alpha = history_column(pad%record, 'alpha_mm')
    compression = history_column(pad%record, 'pad_compression_mm')
    ratio_rigid = value_of(rigid, 'alpha_max_mm')/(1.0e3_dp*hertz_rigid%alpha_max)
    ratio_pad = maxval(alpha + compression)/(1.0e3_dp*hertz_pad%alpha_max)
    print '(a)', ''
    print '(a)', '| V = 0.2 m/s, level 2 | FE approach (mm) | Hertz alpha_m (mm) | ratio |'
    print '(a)', '|---|---|---|---|'
    print '(a)', '| rigid plate, E/(1 - nu^2) | '//fx(value_of(rigid, 'alpha_max_mm'), 5)//' | '// &
      fx(1.0e3_dp*hertz_rigid%alpha_max, 5)//' | '//fx(ratio_rigid, 4)//' |'
    print '(a)', '| pad of the same flesh, 36.6 mm thick, E* | '//fx(maxval(alpha + compression), 5)//' | '// &
      fx(1.0e3_dp*hertz_pad%alpha_max, 5)//' | '//fx(ratio_pad, 4)//' |'
    call check_close('Hertz with the combined modulus: the pad''s FE/Hertz ratio follows the rigid plate''s (3 %)', &
                     ratio_pad, ratio_rigid, 0.03_dp)
    print '(a)', 'fruit alpha_m '//fx(value_of(pad, 'alpha_max_mm'), 5)//' mm, pad compression '// &
      fx(value_of(pad, 'pad_compression_max_mm'), 5)//' mm (Hertz, equal materials: equal shares)'
    call check_close('Hertz with equal materials: the fruit and the pad share the approach (3 %)', &
                     value_of(pad, 'alpha_max_mm'), value_of(pad, 'pad_compression_max_mm'), 0.03_dp)
  end subroutine hertz_combined

  !> 4b. A cover on the pad.
  subroutine covered_pads()
    type(run_t) :: plain, same, stiff
    character(*), parameter :: foam = 'MATERIAL foam ELASTIC E=5.433e6 NU=0.3 RHO=100'
    character(*), parameter :: belt = 'MATERIAL belt ELASTIC E=50e6 NU=0.45 RHO=1200'
    character(len=line_length), allocatable :: lines(:)
    character(*), parameter :: keys(3) = [character(len=12) :: 'alpha_max_mm', 'q_max_MPa', 'force_max_N']
    integer :: k
    plain = run_case('cover_none', impact_lines('1', '0.9982', 'PLATE Z=0 SLIP RELEASE=YES', 'STOP AT=SEPARATION', &
                     foam, 'PAD THICKNESS=0.01 MAT=foam'))
    same = run_case('cover_same', impact_lines('1', '0.9982', 'PLATE Z=0 SLIP RELEASE=YES', 'STOP AT=SEPARATION', &
                    foam, 'PAD THICKNESS=0.01 MAT=foam COVER=0.001 COVERMAT=foam'))
    lines = impact_lines('1', '0.9982', 'PLATE Z=0 SLIP RELEASE=YES', 'STOP AT=SEPARATION', foam, &
                         'PAD THICKNESS=0.01 MAT=foam COVER=0.001 COVERMAT=belt')
    stiff = run_case('cover_belt', [character(len=line_length) :: lines, belt])
    if (.not. (plain%ok .and. same%ok .and. stiff%ok)) return
    print '(a)', ''
    print '(a)', '| 10 mm pad, E = 0.3 E_fruit | alpha_m (mm) | q_m (MPa) | F_m (N) | pad compression (mm) |'
    print '(a)', '|---|---|---|---|---|'
    print '(a)', '| no cover | '//fx(value_of(plain, 'alpha_max_mm'), 4)//' | '//fx(value_of(plain, 'q_max_MPa'), 4)// &
      ' | '//fx(value_of(plain, 'force_max_N'), 2)//' | '//fx(value_of(plain, 'pad_compression_max_mm'), 4)//' |'
    print '(a)', '| 1 mm cover of the same foam | '//fx(value_of(same, 'alpha_max_mm'), 4)//' | '// &
      fx(value_of(same, 'q_max_MPa'), 4)//' | '//fx(value_of(same, 'force_max_N'), 2)//' | '// &
      fx(value_of(same, 'pad_compression_max_mm'), 4)//' |'
    print '(a)', '| 1 mm belt, 50 MPa | '//fx(value_of(stiff, 'alpha_max_mm'), 4)//' | '// &
      fx(value_of(stiff, 'q_max_MPa'), 4)//' | '//fx(value_of(stiff, 'force_max_N'), 2)//' | '// &
      fx(value_of(stiff, 'pad_compression_max_mm'), 4)//' |'
    do k = 1, size(keys)
      call check_close('a cover of the pad''s own material: '//trim(keys(k))//' of the plain pad (2 %)', &
                       value_of(same, trim(keys(k))), value_of(plain, trim(keys(k))), 0.02_dp)
    end do
    call check('a stiff cover spreads the load: q_m lower', value_of(stiff, 'q_max_MPa') < value_of(plain, 'q_max_MPa'))
  end subroutine covered_pads

  !> The static deck: the sphere pressed 0.5 mm by its top node, with `pad` lines (none: the rigid plate).
  function static_lines(pad_material, pad) result(lines)
    character(*), intent(in) :: pad_material, pad
    character(len=line_length), allocatable :: lines(:)
    integer :: count
    count = 6
    if (len(pad) > 0) count = 8
    allocate(lines(count))
    lines(1:6) = [character(len=line_length) :: 'ANALYSIS STATIC', 'GEOMETRY AXISYMMETRIC', fruit, &
                  'MESH SPHERE R=0.0366 LEVEL=2 MAT=apple', 'PLATE Z=0 SLIP', 'FIX TOP Z UZ=-0.0005']
    if (len(pad) > 0) lines(7:8) = [character(len=line_length) :: pad_material, pad]
  end function static_lines

  !> 5. Static indentation on a pad.
  subroutine static_pads()
    type(deck_t) :: deck
    type(record_t) :: rigid, stiff, flesh
    type(error_t), allocatable :: error
    real(dp) :: force(3), alpha(3), compression(2:3)
    call run_static('static_rigid', static_lines('', ''), rigid)
    call run_static('static_stiff', static_lines('MATERIAL stiff ELASTIC E=18.11e9 NU=0.3 RHO=1000', &
                    'PAD THICKNESS=0.01 MAT=stiff'), stiff)
    call run_static('static_flesh', static_lines('MATERIAL flesh ELASTIC E=18.11e6 NU=0.219 RHO=756.85', &
                    'PAD THICKNESS=0.02 MAT=flesh'), flesh)
    force = [summary_real(rigid, 'force_N'), summary_real(stiff, 'force_N'), summary_real(flesh, 'force_N')]
    alpha = [summary_real(rigid, 'alpha_mm'), summary_real(stiff, 'alpha_mm'), summary_real(flesh, 'alpha_mm')]
    ! read before the print: a missing key reports a FAIL, which cannot be printed from inside a print
    compression = [summary_real(stiff, 'pad_compression_mm'), summary_real(flesh, 'pad_compression_mm')]
    print '(a)', ''
    print '(a)', '| STATIC, top pressed 0.5 mm | force (N) | alpha (mm) | pad compression (mm) |'
    print '(a)', '|---|---|---|---|'
    print '(a)', '| rigid plate | '//fx(force(1), 4)//' | '//fx(alpha(1), 5)//' | - |'
    print '(a)', '| pad 1000 E, 10 mm | '//fx(force(2), 4)//' | '//fx(alpha(2), 5)//' | '// &
      fx(compression(2), 6)//' |'
    print '(a)', '| pad of flesh, 20 mm | '//fx(force(3), 4)//' | '//fx(alpha(3), 5)//' | '// &
      fx(compression(3), 5)//' |'
    call check_close('static stiff pad: the rigid plate''s force (0.5 %)', force(2), force(1), 5.0e-3_dp)
    call check_close('static stiff pad: the rigid plate''s alpha (0.5 %)', alpha(2), alpha(1), 5.0e-3_dp)
    call check('static flesh pad: a smaller force at the same travel', force(3) < force(1))
    call static_hertz()
    call static_lift_off()
  end subroutine static_pads

  !> Static indentation on a thick pad, the sphere pressed by GRAVITY alone
  !> (resting on the pad: its rigid translation is solved for), level 3, against
  !> Hertz with the combined modulus, beside the rigid plate against Hertz.
  subroutine static_hertz()
    type(record_t) :: rigid, pad
    character(len=8), parameter :: gravity(2) = [character(len=8) :: '20', '200']
    real(dp), parameter :: allowed(2) = [0.01_dp, 0.02_dp]
    real(dp) :: force, approach, ratio_rigid, ratio_pad, a_over_r, combined, share
    type(hertz_t) :: hertz
    integer :: k
    print '(a)', ''
    print '(a)', '| STATIC, pressed by gravity, level 3 | a/R | rigid: alpha/alpha_H(E/(1-nu^2)) | pad of flesh: '// &
                 '(alpha + compression)/alpha_H(E*) | fruit alpha / pad compression |'
    print '(a)', '|---|---|---|---|---|'
    do k = 1, 2
      call run_static('static_gravity_rigid_'//trim(gravity(k)), [character(len=line_length) :: 'ANALYSIS STATIC', &
                      'GEOMETRY AXISYMMETRIC', fruit, 'MESH SPHERE R=0.0366 LEVEL=3 MAT=apple', 'PLATE Z=0 SLIP', &
                      'GRAVITY G='//trim(gravity(k))], rigid)
      call run_static('static_gravity_pad_'//trim(gravity(k)), [character(len=line_length) :: 'ANALYSIS STATIC', &
                      'GEOMETRY AXISYMMETRIC', fruit, 'MESH SPHERE R=0.0366 LEVEL=3 MAT=apple', 'PLATE Z=0 SLIP', &
                      'GRAVITY G='//trim(gravity(k)), 'MATERIAL flesh ELASTIC E=18.11e6 NU=0.219 RHO=1e-3', &
                      'PAD THICKNESS=0.0366 WIDTH=0.1 MAT=flesh BOTTOM=SLIP'], pad)
      force = summary_real(rigid, 'force_N')
      call check_close('static on the pad alone: the pad carries the weight ('//trim(gravity(k))//')', &
                       summary_real(pad, 'force_N'), force, 1.0e-9_dp)
      hertz = static_hertz_alpha(young/(1.0_dp - poisson**2), force)
      a_over_r = sqrt(radius*hertz%alpha_max)/radius
      ratio_rigid = 1.0e-3_dp*summary_real(rigid, 'alpha_mm')/hertz%alpha_max
      combined = 1.0_dp/(2.0_dp*(1.0_dp - poisson**2)/young)
      approach = 1.0e-3_dp*(summary_real(pad, 'alpha_mm') + summary_real(pad, 'pad_compression_mm'))
      hertz = static_hertz_alpha(combined, force)
      ratio_pad = approach/hertz%alpha_max
      share = summary_real(pad, 'alpha_mm')/summary_real(pad, 'pad_compression_mm')   ! not inside the print
      print '(a)', '| G = '//trim(gravity(k))//' | '//fx(a_over_r, 3)//' | '//fx(ratio_rigid, 4)//' | '// &
        fx(ratio_pad, 4)//' | '//fx(share, 4)//' |'
      call check_close('static Hertz with E*: the pad''s ratio follows the rigid plate''s (a/R = '//fx(a_over_r, 3)// &
                       ')', ratio_pad, ratio_rigid, allowed(k))
      call check_close('static, equal materials: the fruit and the pad share the approach (a/R = '// &
                       fx(a_over_r, 3)//', 1 %)', summary_real(pad, 'alpha_mm'), summary_real(pad, 'pad_compression_mm'), &
                       0.01_dp)
    end do
  end subroutine static_hertz

  !> A body resting on the pad alone whose pole is pulled up (FORCE at node
  !> 96, the level-1 sphere's pole) would be free: a located error at the PAD card.
  subroutine static_lift_off()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    call read_deck(deck_file('static_lift_off', [character(len=line_length) :: 'ANALYSIS STATIC', &
                   'GEOMETRY AXISYMMETRIC', fruit, 'MESH SPHERE R=0.0366 LEVEL=1 MAT=apple', 'PLATE Z=0 SLIP RELEASE=YES', &
                   'GRAVITY G=20', 'FORCE 96 FR=0 FZ=5', 'MATERIAL flesh ELASTIC E=18.11e6 NU=0.219 RHO=1e-3', &
                   'PAD THICKNESS=0.0366 WIDTH=0.1 MAT=flesh BOTTOM=SLIP']), deck, error)
    call check('static lift-off: the deck reads', .not. allocated(error), message_of(error))
    if (allocated(error)) return
    call check('static lift-off: node 96 is the pole', deck%mesh%xy(1, 96) == 0.0_dp .and. deck%mesh%xy(2, 96) == 0.0_dp)
    call solve_static_contact(deck, record, error)
    call check('static lift-off: refused', allocated(error))
    if (allocated(error)) call check_text_contains('static lift-off: says why, at the PAD card', error_text(error), &
                                                   ':10: PAD: the body has lifted off the pad, which alone holds it')
    call static_ring_contact()
  end subroutine static_lift_off

  !> A body on the pad alone whose pole lifts while a ring of nodes still
  !> holds it (a stiff cover on soft foam, STICK: the cover bridges under the
  !> pole): the anchor moves to the held node nearest the axis and the run
  !> goes on. The pad must then carry the body's weight, M g, to round-off,
  !> and the solution pass solve_static_contact's equilibrium check.
  subroutine static_ring_contact()
    type(record_t) :: record
    real(dp), parameter :: mass = 4.0_dp/3.0_dp*pi*0.03_dp**3*900.0_dp, gravity = 500.0_dp
    call run_static('static_ring_contact', [character(len=line_length) :: 'ANALYSIS STATIC', &
                    'GEOMETRY AXISYMMETRIC', 'MATERIAL flesh ELASTIC E=5e6 NU=0.3 RHO=900', &
                    'MATERIAL foam ELASTIC E=1e6 NU=0.3 RHO=100', 'MATERIAL belt ELASTIC E=20e6 NU=0.45 RHO=1200', &
                    'MESH SPHERE R=0.03 LEVEL=1 MAT=flesh', 'PLATE Z=0 STICK', &
                    'PAD THICKNESS=0.008 MAT=foam COVER=0.001 COVERMAT=belt WIDTH=0.04 SIZE=0.002 BOTTOM=SLIP', &
                    'GRAVITY G=500'], record)
    call check_close('static, the pole lifted: the pad carries the weight M g', summary_real(record, 'force_N'), &
                     mass*gravity, 1.0e-9_dp)
  end subroutine static_ring_contact

  !> Hertz's static approach of a sphere of radius `radius` pressed with
  !> `force` on a half-space of plane-strain modulus `modulus`: alpha =
  !> (9 F^2 / (16 E*^2 R))^(1/3) (in alpha_max; the other fields unused).
  pure function static_hertz_alpha(modulus, force) result(hertz)
    real(dp), intent(in) :: modulus, force
    type(hertz_t) :: hertz
    hertz%alpha_max = (9.0_dp*force**2/(16.0_dp*modulus**2*radius))**(1.0_dp/3.0_dp)
  end function static_hertz_alpha

  !> Read and run a static contact deck (a failed check if it does not run).
  subroutine run_static(name, body, record)
    character(*), intent(in) :: name
    character(len=line_length), intent(in) :: body(:)
    type(record_t), intent(out) :: record
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    call read_deck(deck_file(name, body), deck, error)
    if (.not. allocated(error)) call solve_static_contact(deck, record, error)
    if (allocated(error)) call check('run_'//name, .false., error_text(error))
  end subroutine run_static


  !> 6. Decks a PAD cannot run.
  subroutine bad_pads()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    call read_deck(deck_file('no_plate', impact_lines('1', '1', 'OUTPUT EVERY=1', 'PROBE centre R=0 Z=0.0366', &
                   'MATERIAL foam ELASTIC E=1e6 NU=0.3 RHO=100', 'PAD THICKNESS=0.01 MAT=foam')), deck, error)
    call check('a PAD needs a PLATE', allocated(error))
    if (allocated(error)) call check_text_contains('a PAD needs a PLATE: says so', error_text(error), 'PAD needs a PLATE')
    if (allocated(error)) deallocate(error)
    call read_deck(deck_file('unknown_material', impact_lines('1', '1', 'PLATE Z=0', 'STOP AT=MAXDEFORMATION', &
                   'MATERIAL foam ELASTIC E=1e6 NU=0.3 RHO=100', 'PAD THICKNESS=0.01 MAT=rubber')), deck, error)
    call check('an unknown pad material is an error', allocated(error))
    if (allocated(error)) call check_text_contains('an unknown pad material: names it', error_text(error), 'RUBBER')
  end subroutine bad_pads
end program test_pad
