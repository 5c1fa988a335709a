!> Bad card decks: every class of input error must be reported as
!> `file:line:col: CARD: message` with the right file, line, card and message,
!> and a failed run must leave nothing in the output root. A valid deck
!> written loosely (lower case, extra spaces, `NAME = value`, tabs, comments)
!> must parse to the intended model.
program test_bad_decks
  use visco2d_kinds, only: dp, geometry_plane_strain, formulation_bbar
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck, analysis_static, analysis_dynamic, initial_velocity, &
                         stop_at_max_deformation, stop_at_separation
  use visco2d_driver, only: run_deck
  use visco2d_record, only: record_t
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, read_lines
  use visco2d_test_decks, only: deck_line_length, square, creep, dynamic, impact, press, try_read_deck, &
                                check_error_location
  implicit none

  character(*), parameter :: folder = 'build/test_decks/bad'
  character(*), parameter :: out_root = 'build/test_decks/bad_out'
  character(len=deck_line_length), allocatable :: lines(:)
  character(len=1), parameter :: tab = achar(9)

  call execute_command_line('rm -rf '//folder//' '//out_root)
  call execute_command_line('mkdir -p '//folder//' '//out_root)

  ! ---------------------------------------------------------------- card syntax
  lines = [character(len=deck_line_length) :: &
    '# a comment line and a blank line come first: they still count', &  ! 1
    '', &                                                                  ! 2
    'TITLE t', &                                                           ! 3
    'ANALYSIS STATIC', &                                                   ! 4
    '! another comment', &                                                 ! 5
    '  foo 1 2', &                                                         ! 6
    'END']
  call expect_read_error('unknown_card', lines, 6, 3, 'FOO', 'unknown card "FOO"')

  lines = square()
  lines(10) = 'FIX 1 RZ FOO=3'
  call expect_read_error('unknown_field', lines, 10, 10, 'FIX', 'unknown field FOO')

  lines = square()
  lines(10) = 'FIX 1 RZ 7'
  call expect_read_error('surplus_positional', lines, 10, 10, 'FIX', 'unexpected value "7"')

  lines = square()
  lines(4) = 'MATERIAL steel ELASTIC E=abc NU=0.3'
  call expect_read_error('non_numeric_e', lines, 4, 24, 'MATERIAL', 'E must be a number, got "abc"')

  lines = square()
  lines(6) = 'NODE 2 1.2.3 0'
  call expect_read_error('non_numeric_coordinate', lines, 6, 8, 'NODE', &
                         'r coordinate must be a number, got "1.2.3"')

  lines = square()
  lines(4) = 'MATERIAL steel ELASTIC E=200e9 NU=0.7'
  call expect_read_error('nu_out_of_range', lines, 4, 32, 'MATERIAL', 'NU must be in (-1, 0.5), got 0.7')

  lines = square()
  lines(4) = 'MATERIAL steel ELASTIC NU=0.3 E=-1'
  call expect_read_error('e_not_positive', lines, 4, 31, 'MATERIAL', 'E must be in [0.001, 1e14] Pa, got "-1"')

  lines = square()
  lines(4) = 'MATERIAL steel ELASTIC NU=0.3 E='
  call expect_read_error('no_value_last_field', lines, 4, 31, 'MATERIAL', 'field E has no value')

  lines = square()
  lines(4) = 'MATERIAL steel ELASTIC E= NU=0.3'
  call expect_read_error('no_value_before_next_field', lines, 4, 24, 'MATERIAL', 'field E has no value')

  ! ------------------------------------------------------- missing / duplicated cards
  lines = square()
  call expect_read_error('missing_end', lines(1:11), 11, 1, 'FIX', 'missing END card: the deck ends after this card')

  lines = square()
  call expect_read_error('missing_analysis', [lines(1:1), lines(3:12)], 11, 1, 'END', 'missing ANALYSIS card')

  lines = square()
  lines(9) = 'ELEMENT 1 1 2 3 4'
  call expect_read_error('missing_material', [lines(1:3), lines(5:12)], 8, 1, 'ELEMENT', &
                         'missing MATERIAL card: the elements need one')

  lines = square()
  call expect_read_error('missing_mesh', [lines(1:4), lines(12:12)], 5, 1, 'END', &
                         'missing mesh: give NODE and ELEMENT cards or a MESH card')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:4), 'TITLE again', lines(5:12)]
  call expect_read_error('duplicate_title', lines, 5, 1, 'TITLE', &
                         'only one TITLE card is allowed (first on line 1)')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:9), 'analysis static', lines(10:12)]
  call expect_read_error('duplicate_analysis', lines, 10, 1, 'ANALYSIS', &
                         'only one ANALYSIS card is allowed (first on line 2)')

  ! ------------------------------------------------------------------ mesh checks
  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:9), 'NODE 2 5 5', lines(10:12)]
  call expect_read_error('duplicate_node', lines, 10, 0, 'NODE', 'node 2 defined twice (also on line 6)')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:9), 'ELEMENT 1 1 2 3 4 MAT=steel', lines(10:12)]
  call expect_read_error('duplicate_element', lines, 10, 0, 'ELEMENT', 'element 1 defined twice (also on line 9)')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:4), 'MATERIAL Steel ELASTIC E=1e9 NU=0.3', lines(5:12)]
  call expect_read_error('duplicate_material', lines, 5, 10, 'MATERIAL', 'material STEEL defined twice (first on line 4)')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:9), 'NODE 5 2 0', 'ELEMENT 2 2 5 6 3 MAT=steel', lines(10:12)]
  call expect_read_error('undefined_node', lines, 11, 0, 'ELEMENT', 'element 2 uses node 6, which is not defined')

  lines = square()
  lines(9) = 'ELEMENT 1 1 2 3 4 MAT=wood'
  call expect_read_error('undefined_material', lines, 9, 0, 'ELEMENT', &
                         'element 1 uses material WOOD, which is not defined by a MATERIAL card')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:9), 'NODE 9 5 5', lines(10:12)]
  call expect_read_error('unconnected_node', lines, 10, 0, 'NODE', 'node 9 is not connected to any element')

  lines = square()
  lines(9) = 'ELEMENT 1 1 4 3 2 MAT=steel'
  call expect_read_error('clockwise_element', lines, 9, 0, 'ELEMENT', 'element 1 has a non-positive Jacobian')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:9), 'MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=2 NZ=2', lines(10:12)]
  call expect_read_error('mesh_after_node_cards', lines, 10, 1, 'MESH', &
                         'a MESH card cannot be combined with NODE/ELEMENT cards')

  lines = [character(len=deck_line_length) :: 'TITLE t', 'ANALYSIS STATIC', 'GEOMETRY PLANESTRAIN', &
    'MATERIAL steel ELASTIC E=200e9 NU=0.3', 'MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=2 NZ=2', &
    'NODE 100 0 0', 'FIX BOTTOM RZ', 'END']
  call expect_read_error('node_after_mesh_card', lines, 6, 1, 'NODE', &
                         'NODE cards cannot be combined with the MESH card on line 5')

  ! ------------------------------------- layered fruit: SKINMAT=, SKIN_LAYERS=, COREMAT=
  ! Deck of two materials, the MESH card on line 5 (MAT= at column 20, the
  ! region field after it at column 30, SKIN_LAYERS after SKINMAT=skin at 43).
  call expect_read_error('skinmat_undefined', layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT=wood'), 5, 30, 'MESH', &
                         'uses material WOOD, which is not defined by a MATERIAL card')
  call expect_read_error('coremat_undefined', layered('MESH SPHERE R=0.03 MAT=flesh COREMAT=wood'), 5, 30, 'MESH', &
                         'element 1 uses material WOOD, which is not defined by a MATERIAL card')
  call expect_read_error('coremat_undefined_spheroid', layered('MESH SPHEROID A=0.03 C=0.025 MAT=flesh COREMAT=wood'), &
                         5, 40, 'MESH', 'element 1 uses material WOOD, which is not defined by a MATERIAL card')
  call expect_read_error('skin_layers_without_skinmat', layered('MESH SPHERE R=0.03 MAT=flesh SKIN_LAYERS=2'), &
                         5, 30, 'MESH', 'SKIN_LAYERS= needs SKINMAT=id (the skin''s material)')
  call expect_read_error('skin_layers_with_coremat_only', &
                         layered('MESH SPHERE R=0.03 MAT=flesh COREMAT=skin SKIN_LAYERS=3'), &
                         5, 43, 'MESH', 'SKIN_LAYERS= needs SKINMAT=id (the skin''s material)')
  call expect_read_error('skin_layers_eight', layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT=skin SKIN_LAYERS=8'), &
                         5, 43, 'MESH', 'SKIN_LAYERS must be in 1..7 (of the 8 polar layers at level 1; '// &
                         'level L has 8*2^(L-1)), got 8')
  call expect_read_error('skin_layers_zero', layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT=skin SKIN_LAYERS=0'), &
                         5, 43, 'MESH', 'SKIN_LAYERS must be in 1..7')
  call expect_read_error('skin_layers_negative', layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT=skin SKIN_LAYERS=-3'), &
                         5, 43, 'MESH', 'got -3')
  call expect_read_error('skin_layers_not_integer', layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT=skin SKIN_LAYERS=2.5'), &
                         5, 43, 'MESH', 'SKIN_LAYERS must be an integer, got "2.5"')
  call expect_read_error('skinmat_no_value', layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT= SKIN_LAYERS=1'), &
                         5, 30, 'MESH', 'field SKINMAT has no value')
  call expect_read_error('skinmat_twice', layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT=skin SKINMAT=skin'), &
                         5, 43, 'MESH', 'field SKINMAT given twice (first at column 30)')
  call expect_read_error('skinmat_too_long', &
                         layered('MESH SPHERE R=0.03 MAT=flesh SKINMAT=abcdefghijabcdefghijabcdefghijabc'), &
                         5, 30, 'MESH', 'SKINMAT id longer than 32 characters')
  call expect_read_error('coremat_too_long', &
                         layered('MESH SPHERE R=0.03 MAT=flesh COREMAT=abcdefghijabcdefghijabcdefghijabc'), &
                         5, 30, 'MESH', 'COREMAT id longer than 32 characters')
  call expect_read_error('skinmat_without_mat', layered('MESH SPHERE R=0.03 SKINMAT=skin'), 5, 1, 'MESH', &
                         'element 1 needs MAT=<id>: the deck defines several materials')
  call expect_read_error('skinmat_on_rect', layered('MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=2 NZ=2 MAT=flesh SKINMAT=skin'), &
                         5, 51, 'MESH', 'unknown field SKINMAT')
  call expect_read_error('coremat_on_ring', layered('MESH RING R0=0.01 R1=0.02 NR=2 NT=2 MAT=flesh COREMAT=skin'), &
                         5, 47, 'MESH', 'unknown field COREMAT')

  ! ------------------------------------------------------------- supports and loads
  lines = square()
  lines(10) = 'FIX 1 X'
  call expect_read_error('fix_bad_component', lines, 10, 7, 'FIX', 'components must be R, Z or RZ, got "X"')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:11), 'PRESSURE LEFT P=1e3', lines(12:12)]
  call expect_read_error('pressure_unknown_set', lines, 12, 10, 'PRESSURE', &
                         'edge set must be INNER, OUTER, TOP or BOTTOM, got "LEFT"')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:11), 'PRESSURE P=1e3 LEFT', lines(12:12)]
  call expect_read_error('pressure_unknown_set_after_p', lines, 12, 16, 'PRESSURE', &
                         'edge set must be INNER, OUTER, TOP or BOTTOM, got "LEFT"')

  lines = [character(len=deck_line_length) :: 'TITLE sphere', 'ANALYSIS STATIC', &
    'MATERIAL fruit ELASTIC E=18e6 NU=0.2', 'MESH SPHERE R=0.03', 'PRESSURE INNER P=1e6', 'FIX TOP Z', 'END']
  call expect_read_error('pressure_set_without_edges', lines, 5, 0, 'PRESSURE', &
                         'edge set INNER has no boundary edges in this mesh')

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:11), 'FORCE 9 FZ=-1e3', lines(12:12)]
  call expect_read_error('force_undefined_node', lines, 12, 7, 'FORCE', 'node 9 is not defined')

  ! ------------------------------------------------------------- files
  block
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(*), parameter :: missing = folder//'/does_not_exist.inp'
    call read_deck(missing, deck, error)
    call check('nonexistent_file_error', allocated(error), 'read_deck accepted a file that does not exist')
    if (allocated(error)) then
      call check_text_contains('nonexistent_file_name', error_text(error), missing//': ')
      call check_text_contains('nonexistent_file_message', error_text(error), 'does not exist')
    end if
  end block

  lines = [character(len=deck_line_length) ::]
  call expect_read_error('empty_file', lines, 1, 0, '', 'the deck has no cards: it is an empty file')
  lines = [character(len=deck_line_length) :: '# only comments', '', '   ! and blanks']
  call expect_read_error('comments_only_file', lines, 3, 0, '', 'the deck has no cards: its 3 lines are blank or comments')

  ! ------------------------------------------------------- errors found at solve time
  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:11), 'FORCE 3 FZ=-1e3', 'EXPECT no_such_key 1.0', lines(12:12)]
  call expect_run_error('expect_unknown_key', lines, 13, 'EXPECT', &
                        'key "no_such_key" is not a numeric summary key', column=8)

  lines = square()
  lines = [character(len=deck_line_length) :: lines(1:9), 'FORCE 3 FZ=-1e3', lines(12:12)]
  call expect_run_error('no_supports', lines, 0, '', 'singular')
  call check_no_supports_message()
  ! A sphere with gravity and no support along z: its rigid z translation
  ! passes the factors' pivot test (every solver), so the solve returned
  ! |u| = 4e8 m with exit 0; the out-of-balance check stops it at the MESH card.
  lines = [character(len=deck_line_length) :: 'TITLE free sphere', 'ANALYSIS STATIC', 'GEOMETRY AXISYMMETRIC', &
           'MATERIAL fruit ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL=2', 'GRAVITY G=9.8', &
           'SOLVER CHOLMOD', 'END']
  call expect_run_error('free_sphere_cholmod', lines, 5, 'MESH', 'singular')
  lines(7) = 'SOLVER BAND'
  call expect_run_error('free_sphere_band', lines, 5, 'MESH', 'singular')
  lines(7) = 'SOLVER PROFILE'
  call expect_run_error('free_sphere_profile', lines, 5, 'MESH', 'singular')
  lines(2) = 'ANALYSIS QUASISTATIC'
  lines(7) = 'TIME DT=0.1 TEND=0.2'
  call expect_run_error('free_sphere_quasistatic', lines, 5, 'MESH', 'singular')

  ! --------------------------------------------- a valid deck written loosely
  call loose_deck()

  call execute_command_line('rm -rf '//out_root)
  ! ------------------------------------------ viscoelastic materials, CURVE and TIME cards
  lines = creep()
  lines(4:5) = [character(len=deck_line_length) :: 'PRONY G=1e6 BETA=10', 'MATERIAL flesh VISCOELASTIC K=2e6']
  call expect_read_error('prony_before_material', lines, 4, 1, 'PRONY', 'PRONY must follow its MATERIAL card')

  lines = creep()
  lines(4) = 'MATERIAL flesh ELASTIC E=1e6 NU=0.3'
  call expect_read_error('prony_after_elastic', lines, 5, 1, 'PRONY', 'material FLESH is ELASTIC')

  lines = creep()
  lines(5) = 'PRONY G=1e6 BETA=-1'
  call expect_read_error('prony_negative_beta', lines, 5, 13, 'PRONY', 'BETA must be 0 or in [1e-12, 1e12] 1/s, got "-1"')

  lines = creep()
  lines(5) = 'PRONY G=0 BETA=1'
  call expect_read_error('prony_zero_shear', lines, 5, 7, 'PRONY', 'G must be in [0.001, 1e14] Pa, got "0"')

  lines = creep()
  lines(5) = 'PRONY E=1e6 ALPHA=1'
  call expect_read_error('prony_uniaxial_field_on_viscoelastic', lines, 5, 0, 'PRONY', 'missing field G')

  lines = creep()
  call expect_read_error('viscoelastic_without_prony', [lines(1:4), lines(6:11)], 4, 1, 'MATERIAL', &
                         'needs at least one PRONY G=.. BETA=.. card')

  lines = creep()
  lines(4:5) = [character(len=deck_line_length) :: 'MATERIAL flesh UNIAXIAL NU=0.5', 'PRONY E=1e6 ALPHA=1']
  call expect_read_error('uniaxial_nu', lines, 4, 25, 'MATERIAL', 'NU must be in (-1, 0.5), got 0.5')

  lines = creep()
  lines(4) = 'MATERIAL flesh UNIAXIAL NU=0.25'
  call expect_read_error('uniaxial_with_shear_term', lines, 5, 0, 'PRONY', 'missing field E')

  lines = creep()
  call expect_read_error('quasistatic_without_time', [lines(1:9), lines(11:11)], 2, 0, 'ANALYSIS', &
                         'QUASISTATIC analysis needs a TIME')

  lines = creep()
  lines(2) = 'ANALYSIS STATIC'
  call expect_read_error('time_in_static', lines, 10, 0, 'TIME', 'TIME cards need ANALYSIS QUASISTATIC')

  lines = creep()
  lines(2) = 'ANALYSIS STATIC'
  lines(8) = 'PRESSURE TOP P=1e4'
  call expect_read_error('memory_in_static', [lines(1:9), lines(11:11)], 2, 0, 'ANALYSIS', &
                         'relaxes in time (PRONY terms with BETA > 0): use ANALYSIS QUASISTATIC')

  lines = creep()
  lines(2) = 'ANALYSIS STATIC'
  lines(4:5) = [character(len=deck_line_length) :: 'MATERIAL flesh ELASTIC E=1e6 NU=0.3', '# no terms']
  call expect_read_error('curve_in_static', [lines(1:9), lines(11:11)], 8, 20, 'PRESSURE', &
                         'CURVE= needs a time axis')

  lines = creep()
  lines(8) = 'PRESSURE TOP P=1e4 CURVE=lode'
  call expect_read_error('curve_undefined', lines, 8, 20, 'PRESSURE', 'curve LODE is not defined by a CURVE card')

  lines = creep()
  lines(9) = 'CURVE load 0 0 1'
  call expect_read_error('curve_odd_count', lines, 9, 0, 'CURVE', 'CURVE points come in pairs')

  lines = creep()
  lines(9) = 'CURVE load 0 0 1 1 0.5 2'
  call expect_read_error('curve_not_increasing', lines, 9, 20, 'CURVE', 'curve times must increase strictly')

  lines = creep()
  lines(9) = 'CURVE load 0 0 1 x'
  call expect_read_error('curve_not_a_number', lines, 9, 18, 'CURVE', 'value of point 2 must be a number')

  lines = creep()
  call expect_read_error('curve_twice', [lines(1:9), lines(9:11)], 10, 0, 'CURVE', &
                         'curve LOAD defined twice (first on line 9)')

  lines = creep()
  lines(10) = 'TIME DT=-1 TEND=1'
  call expect_read_error('time_negative_dt', lines, 10, 6, 'TIME', 'DT must be in [1e-12, 1e9] s, got "-1"')

  lines = creep()
  call expect_read_error('time_stage_backwards', [lines(1:10), lines(10:11)], 11, 0, 'TIME', &
                         'TEND must be after the start of this stage')

  lines = creep()
  lines(10) = 'TIME DT=1e-12 TEND=1'
  call expect_read_error('time_too_many_steps', lines, 10, 6, 'TIME', 'would take more than 10000000 steps')

  lines = creep()
  lines(7) = 'FIX BOTTOM Z UR=1e-3'
  call expect_read_error('fix_ur_without_r', lines, 7, 14, 'FIX', 'the components must include R')

  lines = creep()
  lines(7) = 'FIX BOTTOM Z CURVE=load'
  call expect_read_error('fix_curve_without_value', lines, 7, 14, 'FIX', 'which are zero here')

  lines = creep()
  lines(8) = 'FIX TOP Z UZ=-1e-4'
  lines(9) = 'FIX OUTER Z'
  lines(10) = 'TIME DT=0.1 TEND=1'
  call expect_read_error('fix_conflict', lines, 9, 5, 'FIX', &
                         'different prescribed u_z from the FIX card on line 8')

  lines = creep()
  lines(8) = 'FIX TOP RZ UR=1e-4'
  call expect_read_error('fix_ur_on_axis', lines, 8, 12, 'FIX', 'is on the axis, where u_r = 0 always')

  ! ------------------------------------------------------- dynamic and scene cards
  lines = creep()
  lines(2) = 'ANALYSIS EXPLICIT'
  call expect_read_error('analysis_unknown', lines, 2, 10, 'ANALYSIS', 'STATIC, QUASISTATIC or DYNAMIC, got "EXPLICIT"')

  lines = square()
  call expect_read_error('solver_unknown', [lines(1:2), 'SOLVER LU', lines(3:)], 3, 8, 'SOLVER', &
                         'solver must be BAND (the legacy band storage and LAPACK), PROFILE (envelope storage) '// &
                         'or CHOLMOD (sparse, the default), got "LU"')

  lines = square()
  call expect_read_error('solver_twice', [lines(1:2), 'SOLVER BAND', 'SOLVER CHOLMOD', lines(3:)], 4, 0, 'SOLVER', &
                         'only one SOLVER card is allowed (first on line 3)')

  lines = dynamic()
  call expect_read_error('dynamic_without_time', [lines(1:8), lines(10:11)], 2, 0, 'ANALYSIS', &
                         'DYNAMIC analysis needs a TIME DT=.. TEND=.. card')

  lines = dynamic()
  lines(4) = 'MATERIAL flesh ELASTIC E=1e6 NU=0.3'
  call expect_read_error('dynamic_without_density', lines, 4, 0, 'MATERIAL', &
                         'material FLESH has no density: ANALYSIS DYNAMIC needs RHO= > 0')

  lines = square()
  call expect_read_error('gravity_without_density', [lines(1:10), 'GRAVITY', lines(11:)], 4, 0, 'MATERIAL', &
                         'GRAVITY needs RHO= > 0')

  lines = dynamic()
  lines(7) = 'WILSON THETA=0.9'
  call expect_read_error('theta_below_one', lines, 7, 8, 'WILSON', 'THETA must be >= 1')

  lines = dynamic()
  lines(7) = 'WILSON THETA=12'
  call expect_read_error('theta_above_ten', lines, 7, 8, 'WILSON', 'THETA must be <= 10')

  lines = dynamic()
  call expect_read_error('wilson_twice', [lines(1:7), lines(7:11)], 8, 0, 'WILSON', &
                         'only one WILSON card is allowed (first on line 7)')

  lines = dynamic()
  lines(7) = 'INTEGRATOR LEAPFROG'
  call expect_read_error('integrator_unknown', lines, 7, 12, 'INTEGRATOR', &
                         'unknown integrator ''LEAPFROG'': expected WILSON, NEWMARK, HHT, GENERALIZED_ALPHA or BATHE')

  lines = dynamic()
  lines(7) = 'INTEGRATOR NEWMARK BETA=0.25 GAMMA=0.4'
  call expect_read_error('newmark_gamma_below_half', lines, 7, 30, 'INTEGRATOR', 'GAMMA must lie in 0.5 ... 1')

  lines = dynamic()
  lines(7) = 'INTEGRATOR NEWMARK BETA=0'
  call expect_read_error('newmark_explicit', lines, 7, 20, 'INTEGRATOR', 'BETA must lie in 0 < BETA <= 0.5')

  lines = dynamic()
  lines(7) = 'INTEGRATOR HHT ALPHA=-0.1'
  call expect_read_error('hht_alpha_negative', lines, 7, 16, 'INTEGRATOR', 'ALPHA must lie in 0 ... 1/3')

  lines = dynamic()
  lines(7) = 'INTEGRATOR GENERALIZED_ALPHA RHO_INF=1.5'
  call expect_read_error('rho_inf_above_one', lines, 7, 30, 'INTEGRATOR', 'RHO_INF must lie in 0 ... 1')

  lines = dynamic()
  lines(7) = 'INTEGRATOR HHT THETA=1.4'
  call expect_read_error('hht_with_theta', lines, 7, 16, 'INTEGRATOR', 'THETA')

  lines = dynamic()
  call expect_read_error('wilson_and_integrator', [lines(1:7), 'INTEGRATOR BATHE', lines(8:)], 8, 0, 'INTEGRATOR', &
                         'only one')

  lines = creep()
  call expect_read_error('wilson_in_quasistatic', [lines(1:10), 'WILSON THETA=1.4', lines(11:)], 11, 0, 'WILSON', &
                         'WILSON needs ANALYSIS DYNAMIC (this deck is QUASISTATIC)')

  lines = square()
  call expect_read_error('initial_in_static', [lines(1:10), 'INITIAL VZ=-1', lines(11:)], 11, 0, 'INITIAL', &
                         'INITIAL needs ANALYSIS DYNAMIC (this deck is STATIC)')

  lines = dynamic()
  lines(6) = 'INITIAL'
  call expect_read_error('initial_empty', lines, 6, 0, 'INITIAL', 'INITIAL needs at least one of VZ=')

  lines = dynamic()
  lines(6) = 'INITIAL VZ=fast'
  call expect_read_error('initial_not_a_number', lines, 6, 9, 'INITIAL', 'VZ must be a number, got "fast"')

  lines = dynamic()
  call expect_read_error('drop_and_initial', [lines(1:6), 'DROP HEIGHT=0.05', lines(7:11)], 7, 0, 'DROP', &
                         'the INITIAL card on line 6 sets VZ too: give one of them')

  lines = dynamic()
  lines(6) = 'DROP HEIGHT=-0.05'
  call expect_read_error('drop_negative', lines, 6, 6, 'DROP', 'HEIGHT must be 0 or in [1e-9, 1000] m, got "-0.05"')

  lines = dynamic()
  lines(8) = 'GRAVITY G=-9.8'
  call expect_read_error('gravity_negative', lines, 8, 9, 'GRAVITY', 'G must be 0 or in [1e-6, 1e6] m/s^2, got "-9.8"')

  lines = dynamic()
  lines(10) = 'OUTPUT EVERY=0'
  call expect_read_error('output_every_zero', lines, 10, 8, 'OUTPUT', 'EVERY must be >= 1, got 0')

  lines = dynamic()
  lines(10) = 'OUTPUT FIELDS=1e-4,abc'
  call expect_read_error('output_fields_not_a_number', lines, 10, 8, 'OUTPUT', &
                         'FIELDS must be a comma-separated list of times >= 0 s, got "ABC"')

  lines = dynamic()
  lines(10) = 'OUTPUT FIELDS=5e-4,1e-4'
  call expect_read_error('output_fields_decreasing', lines, 10, 8, 'OUTPUT', 'FIELDS times must increase')

  lines = dynamic()
  lines(10) = 'OUTPUT FIELDS=2e-3'
  call expect_read_error('output_fields_after_end', lines, 10, 0, 'OUTPUT', &
                         'FIELDS time 0.002 s is after the end of the run (TEND = 0.001 s)')

  lines = creep()
  call expect_read_error('output_in_quasistatic', [lines(1:10), 'OUTPUT EVERY=2', lines(11:)], 11, 0, 'OUTPUT', &
                         'OUTPUT applies to ANALYSIS DYNAMIC')

  lines = dynamic()
  call expect_read_error('formulation_unknown', [lines(1:3), 'FORMULATION QUAD8', lines(4:11)], 4, 13, &
                         'FORMULATION', 'formulation must be STANDARD or BBAR, got "QUAD8"')

  ! The dynamic deck itself is valid; THETA < 1.37 and a nearly incompressible
  ! material in the standard element are warnings, not errors.
  call expect_valid_dynamic()

  ! ------------------------------------------------------- contact cards: PLATE and STOP
  lines = impact()
  lines(7) = 'PLATE'
  call expect_read_error('plate_without_z', lines, 7, 1, 'PLATE', 'missing field Z=')

  lines = impact()
  lines(7) = 'PLATE Z=abc'
  call expect_read_error('plate_z_not_a_number', lines, 7, 7, 'PLATE', 'Z must be a number, got "abc"')

  lines = impact()
  lines(7) = 'PLATE Z=0 GRIP'
  call expect_read_error('plate_unknown_kind', lines, 7, 11, 'PLATE', &
                         'contact kind must be STICK or SLIP, got "GRIP"')

  lines = impact()
  lines(7) = 'PLATE Z=0 RELEASE=MAYBE'
  call expect_read_error('plate_release_maybe', lines, 7, 11, 'PLATE', 'RELEASE must be YES or NO, got "MAYBE"')

  lines = impact()
  call expect_read_error('plate_twice', [lines(1:7), lines(7:10)], 8, 1, 'PLATE', &
                         'only one PLATE card is allowed (first on line 7)')

  lines = creep()
  call expect_read_error('plate_in_quasistatic', [lines(1:10), 'PLATE Z=0', lines(11:)], 11, 0, 'PLATE', &
                         'PLATE needs ANALYSIS STATIC or DYNAMIC (QUASISTATIC has no contact search)')

  lines = impact()
  lines(8) = 'STOP'
  call expect_read_error('stop_without_at', lines, 8, 1, 'STOP', 'missing field AT=')

  lines = impact()
  lines(8) = 'STOP AT=SOMETIME'
  call expect_read_error('stop_at_unknown', lines, 8, 6, 'STOP', &
                         'AT must be MAXDEFORMATION, SEPARATION or TEND, got "SOMETIME"')

  lines = impact()
  lines(8) = 'STOP AT=SEPARATION'
  call expect_read_error('stop_separation_without_release', lines, 8, 0, 'STOP', &
                         'STOP AT=SEPARATION needs PLATE ... RELEASE=YES (line 7)')

  lines = impact()
  call expect_read_error('stop_maxdeformation_without_plate', [lines(1:6), lines(8:10)], 7, 0, 'STOP', &
                         'STOP AT=MAXDEFORMATION needs a PLATE card (or use STOP AT=TEND)')

  lines = press()
  call expect_read_error('stop_in_static', [lines(1:7), 'STOP AT=TEND', lines(8:)], 8, 0, 'STOP', &
                         'STOP needs ANALYSIS DYNAMIC (this deck is STATIC)')

  ! The generated sphere's pole (its lowest node) is at z = 0: a plate at 1 mm cuts into it.
  lines = impact()
  lines(7) = 'PLATE Z=0.001'
  call expect_read_error('plate_above_lowest_node', lines, 7, 0, 'PLATE', &
                         'lies below the plate z = 1.0000E-03: the body must start on or above the plate')

  lines = impact()
  lines(7) = 'PLATE Z=0 FOO=1'
  call expect_read_error('plate_unknown_field', lines, 7, 11, 'PLATE', &
                         'unknown field FOO (expected: PLATE Z=.. [STICK | SLIP] [RELEASE=YES|NO])')

  ! ------------------------------------------------------- PAD (a deformable layer on the plate)
  lines = pad_impact('PAD MAT=foam')
  call expect_read_error('pad_without_thickness', lines, 10, 1, 'PAD', 'missing field THICKNESS=')

  lines = pad_impact('PAD THICKNESS=0.01')
  call expect_read_error('pad_without_material', lines, 10, 1, 'PAD', 'missing field MAT=')

  lines = pad_impact('PAD THICKNESS=-0.01 MAT=foam')
  call expect_read_error('pad_thickness_negative', lines, 10, 5, 'PAD', 'THICKNESS')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam BOTTOM=GLUED')
  call expect_read_error('pad_bottom_unknown', lines, 10, 29, 'PAD', 'BOTTOM must be BONDED or SLIP, got "GLUED"')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam FOO=1')
  call expect_read_error('pad_unknown_field', lines, 10, 29, 'PAD', 'unknown field FOO')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam')
  call expect_read_error('pad_twice', [lines(1:10), lines(10:)], 11, 1, 'PAD', &
                         'only one PAD card is allowed (first on line 10)')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=rubber')
  call expect_read_error('pad_material_undefined', lines, 10, 20, 'PAD', &
                         'the pad''s material RUBBER is not defined by a MATERIAL card')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam')
  lines(9) = 'MATERIAL foam ELASTIC E=1e6 NU=0.3'
  call expect_read_error('pad_material_without_density', lines, 9, 0, 'MATERIAL', 'has no density')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam SIZE=0.05')
  call expect_read_error('pad_size_too_coarse', lines, 10, 29, 'PAD', 'is too coarse for a pad')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam COVER=0.001')
  call expect_read_error('pad_cover_without_material', lines, 10, 29, 'PAD', 'COVER= (the top layer''s thickness) and')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam COVER=0.01 COVERMAT=foam')
  call expect_read_error('pad_cover_too_thick', lines, 10, 29, 'PAD', 'COVER must be less than THICKNESS')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam COVER=0.001 COVERMAT=belt')
  call expect_read_error('pad_cover_material_undefined', lines, 10, 41, 'PAD', &
                         'the cover''s material BELT is not defined by a MATERIAL card')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam SIZE=1e-6')
  call expect_read_error('pad_size_too_fine', lines, 10, 29, 'PAD', 'is too fine: the pad would need more than 2000')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam')
  lines(3) = 'GEOMETRY PLANESTRAIN'
  call expect_read_error('pad_plane_strain', lines, 10, 0, 'PAD', 'PAD needs GEOMETRY AXISYMMETRIC')

  lines = pad_impact('PAD THICKNESS=0.01 MAT=foam')
  call expect_read_error('pad_without_plate', [lines(1:6), lines(8:)], 9, 0, 'PAD', 'PAD needs a PLATE card')


  ! The contact decks themselves are valid and parse to the intended settings.
  call expect_valid_contact()

  deallocate(lines)
  call test_summary('test_bad_decks')

contains

  !> The impact deck with a pad: the mesh named MAT=apple (line 5), a foam
  !> material on line 9, `pad` on line 10, TIME on 11, END on 12.
  function pad_impact(pad) result(deck_lines)
    character(*), intent(in) :: pad
    character(len=deck_line_length), allocatable :: deck_lines(:)
    character(len=deck_line_length), allocatable :: base(:)
    base = impact()
    base(5) = 'MESH SPHERE R=0.0381 LEVEL=1 MAT=apple'
    allocate(deck_lines(12))
    deck_lines(1:8) = base(1:8)
    deck_lines(9) = 'MATERIAL foam ELASTIC E=1e6 NU=0.3 RHO=100'
    deck_lines(10) = pad
    deck_lines(11:12) = base(9:10)
  end function pad_impact

  !> The contact decks parse: STICK, RELEASE=NO and STOP AT=MAXDEFORMATION by
  !> default with a plate in DYNAMIC; SLIP RELEASE=YES with STOP AT=SEPARATION;
  !> a plate in STATIC; the plate may sit below the body.
  subroutine expect_valid_contact()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = impact()
    call write_deck(deck_path('contact_default'), [deck_lines(1:7), deck_lines(9:10)])
    call read_deck(deck_path('contact_default'), deck, error)
    call check('contact_default_reads', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    call check('contact_default_plate_line', deck%plate%line == 7)
    call check_close('contact_default_plate_z', deck%plate%z, 0.0_dp, 0.0_dp)
    call check('contact_default_stick', deck%plate%stick .and. .not. deck%plate%release)
    call check('contact_default_stop', deck%stop_at == stop_at_max_deformation)

    deck_lines(7) = 'plate z = -0.002 slip release = yes'
    deck_lines(8) = 'stop at=separation'
    call write_deck(deck_path('contact_separation'), deck_lines)
    call read_deck(deck_path('contact_separation'), deck, error)
    call check('contact_separation_reads', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    call check_close('contact_separation_plate_z', deck%plate%z, -0.002_dp, 0.0_dp)
    call check('contact_separation_slip_release', .not. deck%plate%stick .and. deck%plate%release)
    call check('contact_separation_stop', deck%stop_at == stop_at_separation)

    call write_deck(deck_path('contact_static'), press())
    call read_deck(deck_path('contact_static'), deck, error)
    call check('contact_static_reads', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    call check('contact_static_plate', deck%plate%line == 7 .and. .not. deck%plate%stick)
    call check('contact_static_analysis', deck%analysis == analysis_static)
  end subroutine expect_valid_contact

  !> The dynamic deck parses to the intended settings; warnings for theta < 1.37
  !> and for nu = 0.4999 in the standard element (not in B-bar); DROP gives -sqrt(2 g h).
  subroutine expect_valid_dynamic()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = dynamic()
    call write_deck(deck_path('dynamic_valid'), deck_lines)
    call read_deck(deck_path('dynamic_valid'), deck, error)
    call check('dynamic_valid_reads', .not. allocated(error))
    if (allocated(error)) return
    call check('dynamic_valid_analysis', deck%analysis == analysis_dynamic)
    call check_close('dynamic_valid_theta', deck%dynamics%theta, 1.4_dp, 0.0_dp)
    call check_close('dynamic_valid_gravity', deck%loads%gravity, 9.8_dp, 0.0_dp)
    call check('dynamic_valid_velocity', all(initial_velocity(deck) == [0.0_dp, -1.0_dp]))
    call check('dynamic_valid_every', deck%output%every == 10)
    call check('dynamic_valid_fields', size(deck%output%field_times) == 2)
    call check('dynamic_valid_no_warning', size(deck%warnings) == 0)

    deck_lines(6) = 'DROP HEIGHT=0.05'
    deck_lines(7) = 'WILSON THETA=1.2'
    call write_deck(deck_path('dynamic_drop'), deck_lines)
    call read_deck(deck_path('dynamic_drop'), deck, error)
    call check('dynamic_drop_reads', .not. allocated(error))
    if (allocated(error)) return
    associate (velocity => initial_velocity(deck))
    call check_close('dynamic_drop_vz', velocity(2), -sqrt(2.0_dp*9.8_dp*0.05_dp), 1.0e-15_dp)
    end associate
    call check('dynamic_theta_warning', size(deck%warnings) == 1)
    if (size(deck%warnings) == 1) call check_text_contains('dynamic_theta_warning_text', deck%warnings(1)%text, &
      deck_path('dynamic_drop')//':7: WILSON: THETA = 1.2 < 1.37')

    deck_lines = dynamic()
    deck_lines(4) = 'MATERIAL flesh ELASTIC E=1e6 NU=0.4999 RHO=800'
    call write_deck(deck_path('dynamic_locking'), deck_lines)
    call read_deck(deck_path('dynamic_locking'), deck, error)
    call check('dynamic_locking_reads', .not. allocated(error))
    if (allocated(error)) return
    call check('dynamic_locking_warning', size(deck%warnings) == 1)
    if (size(deck%warnings) == 1) call check_text_contains('dynamic_locking_warning_text', deck%warnings(1)%text, &
      ':4: MATERIAL: material FLESH is nearly incompressible')
    call write_deck(deck_path('dynamic_bbar'), [deck_lines(1:3), 'FORMULATION BBAR', deck_lines(4:)])
    call read_deck(deck_path('dynamic_bbar'), deck, error)
    call check('dynamic_bbar_reads', .not. allocated(error))
    if (allocated(error)) return
    call check('dynamic_bbar_no_warning', size(deck%warnings) == 0)
    call check('dynamic_bbar_formulation', deck%settings%formulation == formulation_bbar)
  end subroutine expect_valid_dynamic

  function deck_path(name) result(path)
    character(*), intent(in) :: name
    character(:), allocatable :: path
    path = folder//'/'//name//'.inp'
  end function deck_path

  !> A static deck of two materials (flesh, skin) with `mesh` on line 5.
  function layered(mesh) result(lines)
    character(*), intent(in) :: mesh
    character(len=deck_line_length), allocatable :: lines(:)
    lines = [character(len=deck_line_length) :: 'TITLE layered', 'ANALYSIS STATIC', &
      'MATERIAL flesh ELASTIC E=3e6 NU=0.3', 'MATERIAL skin ELASTIC E=30e6 NU=0.3', mesh, &
      'PRESSURE OUTER P=1e3', 'FIX TOP Z', 'END']
  end function layered

  !> read_deck must fail with `path:line[:column]: CARD: ...fragment...`.
  !> column = 0: the error must still carry the line, any column is accepted.
  subroutine expect_read_error(name, deck_lines, line, column, card, fragment)
    character(*), intent(in) :: name
    character(*), intent(in) :: deck_lines(:)
    integer, intent(in) :: line, column
    character(*), intent(in) :: card, fragment
    character(:), allocatable :: path, text
    logical :: refused
    path = deck_path(name)
    call try_read_deck(path, refused, text, deck_lines)
    call check(name//'_error', refused, 'read_deck accepted '//path)
    if (refused) call check_error_location(name, text, path, line, column, card, fragment)
  end subroutine expect_read_error

  !> A deck that reads but fails in run_deck: the error is located, and the
  !> output root is left exactly as it was (empty: no case folder, no hidden
  !> partial folder).
  subroutine expect_run_error(name, deck_lines, line, card, fragment, column)
    character(*), intent(in) :: name
    character(*), intent(in) :: deck_lines(:)
    integer, intent(in) :: line
    character(*), intent(in) :: card, fragment
    integer, intent(in), optional :: column
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: path, entries
    path = deck_path(name)
    call write_deck(path, deck_lines)
    call read_deck(path, deck, error)
    call check(name//'_reads', .not. allocated(error), 'the deck should read cleanly before it is run')
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    call run_deck(path, out_root, record, error)
    call check(name//'_error', allocated(error), 'run_deck accepted '//path)
    if (allocated(error)) then
      if (present(column)) then
        call check_error_location(name, error_text(error), path, line, column, card, fragment)
      else
        call check_error_location(name, error_text(error), path, line, 0, card, fragment)
      end if
    end if
    entries = folder_entries(out_root)
    call check(name//'_nothing_left', len(entries) == 0, 'output root '//out_root//' holds: '//entries)
  end subroutine expect_run_error

  !> The rigid-body (no supports) failure must say what to do (FIX) and where.
  subroutine check_no_supports_message()
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: text
    integer :: at
    call run_deck(deck_path('no_supports'), out_root, record, error)
    if (.not. allocated(error)) return   ! already reported by expect_run_error
    text = error_text(error)
    call check_text_contains('no_supports_mentions_fix', text, 'FIX')
    at = index(text, 'at node ')
    call check('no_supports_names_node', at > 0, 'expected "at node <n>" in "'//text//'"')
    if (at > 0) call check('no_supports_node_number', verify(text(at+8:at+8), '0123456789') == 0, &
                           'expected a node number after "at node " in "'//text//'"')
  end subroutine check_no_supports_message

  !> All entries of a folder (hidden ones too), blank-separated; '' if none.
  function folder_entries(path) result(entries)
    character(*), intent(in) :: path
    character(:), allocatable :: entries
    character(*), parameter :: list = 'build/test_decks/bad_listing.txt'
    character(:), allocatable :: names(:)
    logical :: found
    integer :: k
    entries = ''
    call execute_command_line('ls -A '//path//' > '//list//' 2>/dev/null')
    call read_lines(list, names, found, delete=.true.)
    do k = 1, size(names)
      entries = entries//trim(names(k))//' '
    end do
    entries = trim(entries)
  end function folder_entries

  !> Lower-case keywords, extra spaces, `NAME = value`, tabs, # and ! comments.
  subroutine loose_deck()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: path, entries
    character(len=deck_line_length), allocatable :: deck_lines(:)
    logical :: exists
    path = deck_path('loose_valid')
    deck_lines = [character(len=deck_line_length) :: &
      '   title   Loose   deck   # trailing comment', &
      '', &
      'analysis static ! bang comment', &
      'geometry'//tab//'planestrain', &
      'material Steel elastic  E = 200e9'//tab//'nu =0.3   rho= 7800  # comment', &
      'node 1  0   0', &
      'Node'//tab//'2'//tab//'1.0'//tab//'0.0', &
      '  node 3 1 1 ! comment', &
      'NODE 4 0.0 1.0e0', &
      'element 1 1 2 3 4 mat = STEEL', &
      'fix 1 rz', &
      'Fix 2 z', &
      'force 3 fz = -1e3', &
      'probe corner node = 3', &
      '  end  # done']
    call write_deck(path, deck_lines)
    call read_deck(path, deck, error)
    call check('loose_deck_parses', .not. allocated(error), 'got an error')
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    call check('loose_deck_title', deck%title == 'Loose   deck', 'title "'//deck%title//'"')
    call check('loose_deck_analysis', deck%analysis == analysis_static)
    call check('loose_deck_geometry', deck%settings%geometry == geometry_plane_strain)
    call check('loose_deck_one_material', size(deck%materials) == 1)
    if (size(deck%materials) == 1) then
      call check('loose_deck_material_id', deck%materials(1)%id == 'STEEL', 'id "'//deck%materials(1)%id//'"')
      call check_close('loose_deck_e', deck%materials(1)%young, 200.0e9_dp, 1.0e-12_dp)
      call check_close('loose_deck_nu', deck%materials(1)%poisson, 0.3_dp, 1.0e-12_dp)
      call check_close('loose_deck_rho', deck%materials(1)%density, 7800.0_dp, 1.0e-12_dp)
    end if
    call check('loose_deck_nodes', deck%mesh%nnode == 4)
    call check('loose_deck_elements', deck%mesh%nelem == 1)
    if (deck%mesh%nnode == 4) then
      call check_close('loose_deck_node2_r', deck%mesh%xy(1, 2), 1.0_dp, 0.0_dp)
      call check_close('loose_deck_node4_z', deck%mesh%xy(2, 4), 1.0_dp, 0.0_dp)
    end if
    call check('loose_deck_fixes', size(deck%loads%fixes) == 2)
    if (size(deck%loads%fixes) == 2) then
      call check('loose_deck_fix_rz', deck%loads%fixes(1)%fix_r .and. deck%loads%fixes(1)%fix_z)
      call check('loose_deck_fix_z', deck%loads%fixes(2)%fix_z .and. .not. deck%loads%fixes(2)%fix_r)
    end if
    call check('loose_deck_forces', size(deck%loads%forces) == 1)
    if (size(deck%loads%forces) == 1) call check_close('loose_deck_fz', deck%loads%forces(1)%value(2), -1.0e3_dp, &
      1.0e-12_dp)
    call check('loose_deck_probe', size(deck%probes) == 1)
    if (size(deck%probes) == 1) call check('loose_deck_probe_node', deck%probes(1)%node == 3 &
                                           .and. deck%probes(1)%name == 'corner')

    ! The same deck runs and writes a complete case folder (so the failures
    ! above left nothing behind because they failed, not because run_deck never writes).
    call run_deck(path, out_root, record, error)
    call check('loose_deck_runs', .not. allocated(error), 'run_deck failed')
    if (allocated(error)) then
      print '(a)', '  '//error_text(error)
      return
    end if
    inquire(file=out_root//'/loose_valid/summary.txt', exist=exists)
    call check('loose_deck_case_folder', exists, out_root//'/loose_valid/summary.txt is missing')
    entries = folder_entries(out_root)
    call check('loose_deck_only_case_folder', entries == 'loose_valid', 'output root holds: '//entries)
  end subroutine loose_deck
end program test_bad_decks
