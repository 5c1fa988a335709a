!> Limits of the checks that guard a run: the static balance floor against
!> valid decks (a plate that is never touched, a pad 100 m thick), and a
!> pad the small-strain model cannot hold.
program test_limits
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_driver, only: run_deck
  use visco2d_record, only: record_t
  use visco2d_expect, only: summary_value
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, read_lines, &
                             summary_real, message_of
  implicit none

  character(*), parameter :: folder = 'build/test_decks/limits'
  character(*), parameter :: out_root = 'build/test_decks/limits_out'
  integer, parameter :: line_length = 120

  call execute_command_line('mkdir -p '//folder//' '//out_root)
  call untouched_plate()
  call thick_pads()
  call test_summary('test_limits')

contains

  !> A. inputs/sphere_pressure.inp with a PLATE far under it: the plate never
  !> touches, so the contact reactions are all 0 and the body's round-off
  !> residual (6e-13 N) was refused as "not in equilibrium ... singular"
  !> against them. It must run, with the same answer as without the plate.
  subroutine untouched_plate()
    character(:), allocatable :: text(:)
    character(len=line_length), allocatable :: lines(:)
    logical :: found
    type(record_t) :: plain, plated
    type(error_t), allocatable :: error
    integer :: k
    call read_lines('inputs/sphere_pressure.inp', text, found)
    call check('sphere_pressure.inp is found', found)
    if (.not. found) return
    lines = text
    call write_deck(folder//'/sphere_plain.inp', lines)
    do k = size(lines), 1, -1
      if (lines(k)(1:3) == 'END') exit
    end do
    lines = [character(len=line_length) :: lines(1:k - 1), 'PLATE Z=-0.01 SLIP', lines(k:)]
    call write_deck(folder//'/sphere_plate.inp', lines)
    call run_deck(folder//'/sphere_plain.inp', out_root, plain, error)
    call check('sphere under pressure runs', .not. allocated(error), message_of(error))
    if (allocated(error)) deallocate(error)
    call run_deck(folder//'/sphere_plate.inp', out_root, plated, error)
    call check('sphere under pressure with an untouched PLATE runs', .not. allocated(error), message_of(error))
    if (allocated(error)) return
    call check('untouched PLATE: no node on the plate', summary_value(plated, 'contact_nodes') == '0', &
               'contact_nodes = '//summary_value(plated, 'contact_nodes'))
    ! The plate holds nothing, so the solve is the same linear system: the
    ! pole's displacement agrees to round-off (the exact value is
    ! 2 R p (1 - 2 nu)/E, met by the plain deck's EXPECT to 1e-6).
    call check_close('untouched PLATE: the pole moves as without it', summary_real(plated, 'probe_pole_uz_m'), &
                     summary_real(plain, 'probe_pole_uz_m'), rtol=1.0e-12_dp)
  end subroutine untouched_plate

  !> A. STATIC on a PAD 100 m thick (the PAD card's largest THICKNESS). The
  !> body rides down with the pad's compression under its own weight, and
  !> the round-off of that motion, formed through the body's stiffness, was
  !> above 1e-9 of the contact reactions alone: refused with the advice of a
  !> singular stiffness. Against the loads and support reactions (the pad's
  !> weight among them) it is 1.7e-12 of them, and it runs; the body's own
  !> deformation is that of the 37 mm pad (the pad's thickness does not
  !> change the force on the body, its weight).
  subroutine thick_pads()
    type(record_t) :: thin, thick
    type(error_t), allocatable :: error
    character(:), allocatable :: text
    call run_deck(pad_deck('pad_thin', '0.0366', '18.11e6', '100', '9.8'), out_root, thin, error)
    call check('sphere on a 36.6 mm pad runs', .not. allocated(error), message_of(error))
    if (allocated(error)) deallocate(error)
    call run_deck(pad_deck('pad_thick', '100', '18.11e6', '100', '9.8'), out_root, thick, error)
    call check('sphere on a 100 m pad runs (not "singular")', .not. allocated(error), message_of(error))
    if (allocated(error)) deallocate(error)
    ! The force on the plate is the body's weight either way (rtol: round-off
    ! of the contact sums).
    call check_close('100 m pad: force = the 36.6 mm pad''s', summary_real(thick, 'force_N'), &
                     summary_real(thin, 'force_N'), rtol=1.0e-9_dp)
    ! The pad's compression under its own weight: a column of height H,
    ! rho g H^2/(2 E') with E' between E (free sides) and the constrained
    ! modulus E (1-nu)/((1+nu)(1-2nu)) = 1.26 E (nu = 0.219): 0.27 m for
    ! E = 18.11 MPa, rho = 100, H = 100 m; between the two bounds.
    call check('100 m pad: compressed by its own weight (rho g H^2/2E'')', &
               summary_real(thick, 'pad_compression_mm') > 1.0e3_dp*100*9.8*100**2/(2*1.26*18.11e6_dp)*0.9 .and. &
               summary_real(thick, 'pad_compression_mm') < 1.0e3_dp*100*9.8*100**2/(2*18.11e6_dp)*1.1, &
               'pad_compression_mm = '//summary_value(thick, 'pad_compression_mm'))
    ! A 100 m foam pad under G=500 (the fuzz seed seed_pad_static_cover.inp
    ! at THICKNESS=100): its own weight compresses it 251 m, more than its
    ! thickness; once refused as "singular", then (floor on the loads) ran to
    ! exit 0 with pad_compression_mm = 2.5e5. Refused at the PAD card.
    call run_deck(pad_deck('pad_through', '100', '1e6', '100', '500'), out_root, thick, error)
    call check('pad compressed past its thickness is refused', allocated(error))
    if (.not. allocated(error)) return
    text = error_text(error)
    call check_text_contains('pad past its thickness: at the PAD card', text, 'pad_through.inp:9: PAD:')
    call check_text_contains('pad past its thickness: says so', text, 'more than its thickness')
    call check('pad past its thickness: no "singular" advice', index(text, 'singular') == 0, text)
    deallocate(error)
    ! A steel sphere (E = 2e11) on a foam pad (E = 1e5): round-off of 1.1e-7
    ! of the loads (the body rides 1 mm down on the pad, 1.4e6 times its own
    ! deformation), once refused at the 1e-9 floor as "singular". It runs,
    ! and the band and CHOLMOD solutions agree to the round-off the floor
    ! allows (1e-6: measured 1e-8).
    call run_deck(pad_deck('steel_foam_band', '0.01', '1e5', '100', '9.8', '2e11', 'SOLVER BAND'), &
                  out_root, thin, error)
    call check('steel sphere on foam runs (band)', .not. allocated(error), message_of(error))
    if (allocated(error)) deallocate(error)
    call run_deck(pad_deck('steel_foam_cholmod', '0.01', '1e5', '100', '9.8', '2e11', 'SOLVER CHOLMOD'), &
                  out_root, thick, error)
    call check('steel sphere on foam runs (CHOLMOD)', .not. allocated(error), message_of(error))
    if (allocated(error)) deallocate(error)
    call check_close('steel on foam: band and CHOLMOD agree (sigma_z_min)', summary_real(thick, 'sigma_z_min_Pa'), &
                     summary_real(thin, 'sigma_z_min_Pa'), rtol=1.0e-6_dp)
    ! Body and pad moduli 1e9 apart (E = 1e13 on 1e4): round-off of 1.4e-5
    ! of the loads; refused, and the error says it is round-off of a sound
    ! system, at the PAD card, not a singular stiffness.
    call run_deck(pad_deck('pad_soft', '0.01', '1e4', '100', '9.8', '1e13'), out_root, thick, error)
    call check('pad 1e9 times softer than the body is refused', allocated(error))
    if (.not. allocated(error)) return
    text = error_text(error)
    call check_text_contains('soft pad: at the PAD card', text, 'pad_soft.inp:9: PAD:')
    call check_text_contains('soft pad: round-off, not singular', text, 'ill-conditioned system, not a singular')
    call check_text_contains('soft pad: advice', text, 'make the PAD thinner or stiffer')
  end subroutine thick_pads

  !> A sphere (Table 1 size, level 2) resting on a pad under gravity, STATIC.
  function pad_deck(name, thickness, pad_modulus, pad_density, gravity, body_modulus, extra) result(path)
    character(*), intent(in) :: name, thickness, pad_modulus, pad_density, gravity
    character(*), intent(in), optional :: body_modulus, extra
    character(:), allocatable :: path, modulus, last
    modulus = '18.11e6'
    if (present(body_modulus)) modulus = body_modulus
    last = '# no further card'
    if (present(extra)) last = extra
    path = folder//'/'//name//'.inp'
    call write_deck(path, [character(len=line_length) :: 'TITLE sphere on a pad', 'ANALYSIS STATIC', &
      'GEOMETRY AXISYMMETRIC', 'MATERIAL apple ELASTIC E='//modulus//' NU=0.219 RHO=756.85', &
      'MESH SPHERE R=0.0366 LEVEL=2 MAT=apple', 'PLATE Z=0 SLIP', 'GRAVITY G='//gravity, &
      'MATERIAL flesh ELASTIC E='//pad_modulus//' NU=0.219 RHO='//pad_density, &
      'PAD THICKNESS='//thickness//' WIDTH=0.1 MAT=flesh BOTTOM=SLIP', last, 'END'])
  end function pad_deck

end program test_limits
