!> Warnings for decks that run with a meaning the user most likely did not
!> intend: each is located (file:line: CARD: text) and counted in the
!> summary's `warnings` (add_warning). The thresholds and their basis are in
!> doc/robustness.md's warnings table.
!> - DROP HEIGHT= with the body above the plate in gravity: it falls h + gap;
!> - INITIAL VR= in axisymmetry (a breathing motion), FR= on the axis (no effect);
!> - unit slips: RHO below 10 kg/m^3 (g/cm^3?), a fruit body over 1 m in
!>   radius (mm?), a PAD over 1 m thick;
!> - a STATIC or QUASISTATIC deck with no load at all (the answer is zero);
!> - a sphere, spheroid or outline mesh in plane strain (a long cylinder);
!> - a material no element uses.
module visco2d_deck_meaning
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_plane_strain
  use visco2d_strings, only: message_real, short_real
  use visco2d_mesh, only: generated_round_body
  use visco2d_deck_types, only: deck_t, analysis_dynamic, analysis_name, add_warning
  use visco2d_pad_mesh, only: body_nodes
  implicit none
  private

  public :: check_meaning

  !> A density below this (kg/m^3) looks like g/cm^3: the lightest foams are
  !> about 10 kg/m^3, fruit 700-1100 kg/m^3 (0.7-1.1 in g/cm^3).
  real(dp), parameter :: density_floor = 10.0_dp
  !> A generated fruit body wider than this radius (m) looks like mm: the
  !> largest fruit (a big pumpkin) is about 0.5 m in radius.
  real(dp), parameter :: fruit_radius_ceiling = 1.0_dp
  !> A pad thicker than this (m) looks like mm: handling pads are 1-50 mm.
  real(dp), parameter :: pad_thickness_ceiling = 1.0_dp
  !> A gap above the plate of more than this fraction of the DROP height
  !> changes the impact speed sqrt(2 g (h + gap)) by more than 0.5 %.
  real(dp), parameter :: gap_fraction = 0.01_dp

contains

  !> Every check of this module, once the deck is complete (the pad's mesh
  !> too). analysis_line: the ANALYSIS card.
  subroutine check_meaning(deck, analysis_line)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: analysis_line
    call check_drop_gap(deck)
    call check_axis_motion(deck)
    call check_units(deck)
    call check_no_load(deck, analysis_line)
    call check_round_body_in_plane_strain(deck)
    call check_unused_materials(deck)
  end subroutine check_meaning

  !> DROP HEIGHT=h sets VZ = -sqrt(2 g h) at t = 0; a body that starts a gap
  !> above the plate falls h + gap in gravity before it touches.
  subroutine check_drop_gap(deck)
    type(deck_t), intent(inout) :: deck
    real(dp) :: gap, g
    g = deck%loads%gravity
    if (deck%dynamics%drop_line == 0 .or. deck%plate%line == 0 .or. deck%loads%gravity <= 0.0_dp) return
    gap = minval(deck%mesh%xy(2, :body_nodes(deck))) - deck%plate%z
    if (gap <= gap_fraction*deck%dynamics%drop_height .or. gap <= 1.0e-9_dp*deck%mesh%size) return
    call add_warning(deck, deck%dynamics%drop_line, 'DROP', 'the body starts '//message_real(gap)//' m above the plate '// &
      '(PLATE Z = '//short_real(deck%plate%z)//' m): in gravity it falls HEIGHT + gap = '// &
      message_real(deck%dynamics%drop_height + gap)//' m and strikes at '// &
      message_real(sqrt(2.0_dp*g*(deck%dynamics%drop_height + gap)))//' m/s, not the '// &
      message_real(sqrt(2.0_dp*g*deck%dynamics%drop_height))//' m/s of HEIGHT = '//short_real(deck%dynamics%drop_height)// &
      ' m; put the body''s lowest point on the plate, or give the height less the gap')
  end subroutine check_drop_gap

  !> In axisymmetry r is the radius of a ring: INITIAL VR= moves every ring
  !> outward (a breathing motion, not a sideways throw), and a radial FORCE
  !> on the axis acts on a fixed degree of freedom (it does nothing).
  subroutine check_axis_motion(deck)
    type(deck_t), intent(inout) :: deck
    integer :: k
    if (deck%settings%geometry /= geometry_axisymmetric) return
    if (deck%dynamics%initial_line > 0 .and. deck%dynamics%velocity(1) /= 0.0_dp) &
      call add_warning(deck, deck%dynamics%initial_line, 'INITIAL', 'VR = '//short_real(deck%dynamics%velocity(1))// &
        ' m/s in GEOMETRY AXISYMMETRIC is a radial velocity of every ring (the body swells or shrinks, a '// &
        'breathing motion), not a sideways throw: an oblique impact needs GEOMETRY PLANESTRAIN')
    do k = 1, size(deck%loads%forces)
      if (deck%loads%forces(k)%value(1) == 0.0_dp) cycle
      if (deck%mesh%xy(1, deck%loads%forces(k)%node) /= 0.0_dp) cycle
      call add_warning(deck, deck%loads%forces(k)%line, 'FORCE', 'FR = '//short_real(deck%loads%forces(k)%value(1))// &
        ' N on a node on the axis (r = 0) does nothing: u_r = 0 there in GEOMETRY AXISYMMETRIC')
    end do
  end subroutine check_axis_motion

  !> Unit slips: a density in g/cm^3, a fruit radius in mm, a pad in mm.
  subroutine check_units(deck)
    type(deck_t), intent(inout) :: deck
    integer :: k
    real(dp) :: radius
    do k = 1, size(deck%materials)
      associate (material => deck%materials(k))
      if (material%density <= 0.0_dp .or. material%density >= density_floor) cycle
      if (.not. any(deck%mesh%element_material == k)) cycle
      call add_warning(deck, material%line, 'MATERIAL', 'material '//material%id//' has RHO = '// &
        short_real(material%density)//' kg/m^3, lighter than any foam: in g/cm^3 that would be '// &
        message_real(1000.0_dp*material%density)//' kg/m^3 (RHO is in kg/m^3; fruit are 700-1100)')
      end associate
    end do
    if (generated_round_body(deck%mesh)) then
      radius = maxval(abs(deck%mesh%xy(1, :body_nodes(deck))))
      if (radius > fruit_radius_ceiling) call add_warning(deck, deck%mesh%line, 'MESH', 'the body is '// &
        message_real(radius)//' m in radius, larger than any fruit: lengths are in m (a radius of 37 mm is R=0.037)')
    end if
    if (deck%pad%line > 0 .and. deck%pad%thickness > pad_thickness_ceiling) call add_warning(deck, deck%pad%line, &
      'PAD', 'THICKNESS = '//short_real(deck%pad%thickness)//' m is thicker than any handling pad (1-50 mm): '// &
      'lengths are in m (10 mm is THICKNESS=0.01)')
  end subroutine check_units

  !> A STATIC or QUASISTATIC deck with no PRESSURE, FORCE, GRAVITY or
  !> prescribed FIX displacement has the answer zero everywhere.
  subroutine check_no_load(deck, analysis_line)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: analysis_line
    integer :: k
    if (deck%analysis == analysis_dynamic) return
    if (size(deck%loads%pressures) > 0 .or. size(deck%loads%forces) > 0 .or. deck%loads%gravity > 0.0_dp) return
    do k = 1, size(deck%loads%fixes)
      if (any(deck%loads%fixes(k)%value /= 0.0_dp)) return
    end do
    call add_warning(deck, analysis_line, 'ANALYSIS', analysis_name(deck%analysis)//' deck without any load (no '// &
      'PRESSURE, FORCE, GRAVITY or FIX UR=/UZ=): every displacement and stress is zero')
  end subroutine check_no_load

  !> In plane strain a generated sphere (spheroid) is the section of a long
  !> cylinder, per metre of its length: not a sphere.
  subroutine check_round_body_in_plane_strain(deck)
    type(deck_t), intent(inout) :: deck
    if (deck%settings%geometry /= geometry_plane_strain .or. .not. generated_round_body(deck%mesh)) return
    call add_warning(deck, deck%mesh%line, 'MESH', 'in GEOMETRY PLANESTRAIN this '//deck%mesh%source//' is the '// &
      'cross-section of a long cylinder (forces, masses and energies per metre of its length), not a '// &
      deck%mesh%source//'; GEOMETRY AXISYMMETRIC makes it a body of revolution')
  end subroutine check_round_body_in_plane_strain

  !> A MATERIAL card that no element uses (ELEMENT MAT=, MESH MAT=/SKINMAT=/
  !> COREMAT=, PAD MAT=/COVERMAT=): a misspelt or forgotten assignment.
  subroutine check_unused_materials(deck)
    type(deck_t), intent(inout) :: deck
    integer :: k
    do k = 1, size(deck%materials)
      if (any(deck%mesh%element_material == k)) cycle
      call add_warning(deck, deck%materials(k)%line, 'MATERIAL', 'material '//deck%materials(k)%id// &
        ' is used by no element (its properties are ignored): is a MAT= naming another one by mistake?')
    end do
  end subroutine check_unused_materials
end module visco2d_deck_meaning
