!> The cards of the contact extension: PLATE (a rigid flat plate), PAD (a
!> deformable layer on it, meshed by visco2d_pad_mesh), BODY (a second
!> deformable body under the first, meshed by visco2d_body_mesh) and STOP
!> (when a dynamic run ends). Each reader checks its own card; visco2d_deck
!> checks how the cards fit together.
module visco2d_contact_cards
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_ranges, only: length_range, pad_length_range, speed_range
  use visco2d_strings, only: short_real, integer_text
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_word, positional_word, &
                           check_fields_used, has_field, field_column, named_integer
  implicit none
  private

  public :: plate_t, pad_t, body_t, read_plate, read_pad, read_body, read_stop, stop_name
  public :: stop_at_tend, stop_at_max_deformation, stop_at_separation

  integer, parameter :: stop_at_tend = 1             !< run to the end of the last TIME card
  integer, parameter :: stop_at_max_deformation = 2  !< the paper's criterion (and the maximum of alpha)
  integer, parameter :: stop_at_separation = 3       !< run through rebound until the body leaves the plate

  !> PLATE Z=.. [STICK | SLIP] [RELEASE=YES|NO]: a fixed rigid plate z = Z under the body.
  type :: plate_t
    real(dp) :: z = 0.0_dp        !< m
    logical :: stick = .true.     !< STICK: contact nodes held in r and z; SLIP: in z only (frictionless)
    logical :: release = .false.  !< RELEASE=YES: a contact node whose reaction turns tensile is freed
    integer :: line = 0           !< 0: no plate
  end type plate_t

  !> PAD THICKNESS=.. MAT=id [COVER=.. COVERMAT=id] [WIDTH=..] [SIZE=..]
  !> [BOTTOM=BONDED|SLIP]: a deformable layer of material MAT between the
  !> body and the rigid plate, with COVER= a top layer of that thickness
  !> (within THICKNESS) of material COVERMAT, bonded to it (a thin pad on a
  !> thick one: a cover sheet on foam, a belt on its backing).
  !> Its top surface is the PLATE card's Z (where the body touches); it rests
  !> on the rigid plate at Z - THICKNESS. The pad's nodes and elements follow
  !> the body's in the mesh (visco2d_pad_mesh fills in the mesh part).
  type :: pad_t
    real(dp) :: thickness = 0.0_dp   !< m
    real(dp) :: width = 0.0_dp       !< m, radius (half-width in plane strain); 0: the default, 1.5 x the body's
    real(dp) :: size = 0.0_dp        !< m, element size at the impact point; 0: the body's pole edge
    logical :: bonded = .true.       !< BOTTOM=BONDED: bottom held in r and z; SLIP: in z only
    character(:), allocatable :: material    !< MAT= id
    real(dp) :: cover = 0.0_dp       !< m, COVER=: the top layer's thickness (0: none)
    character(:), allocatable :: cover_material   !< COVERMAT= id ('' without a cover)
    integer :: line = 0              !< 0: no pad
    integer :: material_index = 0    !< into deck%materials (once the mesh has the pad)
    integer :: cover_index = 0       !< the cover's material, into deck%materials
    integer :: first_node = 0        !< the pad's nodes are first_node..nnode (0: no pad)
    integer :: first_element = 0     !< the pad's elements are first_element..nelem
    integer, allocatable :: surface(:)   !< the top surface's nodes, by increasing r
    integer, allocatable :: bottom(:)    !< the bottom's nodes (on the rigid plate)
  end type pad_t

  !> BODY SPHERE R=.. MAT=id [LEVEL=L] [VZ=..] [GAP=..] [SLIP | STICK]
  !> [RELEASE=YES|NO]: a second deformable body, a sphere of radius R
  !> meshed like MESH SPHERE R=.. LEVEL=L (the contact grid) but mirrored,
  !> its contact pole on top, on the axis under the first body: its top pole
  !> GAP below the first body's lowest node, its initial velocity VZ (m/s,
  !> positive up). Contact from the first body's surface nodes onto its
  !> upper surface (node to segment, visco2d_contact). Its nodes and
  !> elements follow the first body's in the mesh (visco2d_body_mesh fills
  !> in the mesh part: deck%pad%first_node, first_element, surface).
  type :: body_t
    real(dp) :: radius = 0.0_dp      !< m
    integer :: level = 1             !< the sphere grid's level (1..7)
    character(:), allocatable :: material    !< MAT= id
    real(dp) :: velocity = 0.0_dp    !< m/s, VZ= (positive up, toward the first body)
    real(dp) :: gap = 0.0_dp         !< m, GAP=: from the first body's lowest node down to the top pole
    logical :: stick = .false.       !< STICK: contact nodes tied in r and z; SLIP (default): in z only
    logical :: release = .true.      !< RELEASE=YES (default): a pair whose force turns tensile lets go
    integer :: line = 0              !< 0: no second body
    integer :: material_index = 0    !< into deck%materials (once the mesh has the body)
  end type body_t

contains

  !> BODY SPHERE R=.. MAT=id [LEVEL=L] [VZ=..] [GAP=..] [SLIP | STICK] [RELEASE=YES|NO].
  subroutine read_body(cards, card, body, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(body_t), intent(inout) :: body
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word
    character(len=*), parameter :: form = 'BODY SPHERE R=.. MAT=id [LEVEL=L] [VZ=..] [GAP=..] [SLIP | STICK] '// &
                                          '[RELEASE=YES|NO]'
    call positional_word(cards, card, 1, 'shape (SPHERE)', word, error); if (allocated(error)) return
    if (word /= 'SPHERE') then
      call card_error(error, cards, card, 'the second body''s shape must be SPHERE (the only one so far), got "'// &
                      word//'" (expected: '//form//')', field_column(card, '1')); return
    end if
    call positional_word(cards, card, 2, 'contact kind (SLIP or STICK)', word, error, optional_field=.true.)
    if (allocated(error)) return
    select case (word)
    case ('', 'SLIP')
      body%stick = .false.
    case ('STICK')
      body%stick = .true.
    case default
      call card_error(error, cards, card, 'contact kind must be SLIP or STICK, got "'//word//'"', &
                      field_column(card, '2')); return
    end select
    if (.not. has_field(card, 'R')) then
      call card_error(error, cards, card, 'missing field R= (the second body''s radius; expected: '//form//')'); return
    end if
    if (.not. has_field(card, 'MAT')) then
      call card_error(error, cards, card, 'missing field MAT= (the second body''s material; expected: '//form//')')
      return
    end if
    call named_real(cards, card, 'R', body%radius, error, range=pad_length_range); if (allocated(error)) return
    call named_integer(cards, card, 'LEVEL', body%level, error, default=1); if (allocated(error)) return
    if (body%level < 1 .or. body%level > 7) then
      call card_error(error, cards, card, 'LEVEL must be in 1..7, got '//integer_text(body%level), &
                      field_column(card, 'LEVEL')); return
    end if
    call named_word(cards, card, 'MAT', body%material, error); if (allocated(error)) return
    if (len(body%material) > 32) then
      call card_error(error, cards, card, 'MAT id longer than 32 characters', field_column(card, 'MAT')); return
    end if
    call named_real(cards, card, 'VZ', body%velocity, error, default=0.0_dp, range=speed_range)
    if (allocated(error)) return
    call named_real(cards, card, 'GAP', body%gap, error, default=0.0_dp, range=length_range)
    if (allocated(error)) return
    if (body%gap < 0.0_dp) then
      call card_error(error, cards, card, 'GAP must be 0 or more (the bodies may not overlap at the start), got '// &
                      short_real(body%gap)//' m', field_column(card, 'GAP')); return
    end if
    call named_word(cards, card, 'RELEASE', word, error, default='YES'); if (allocated(error)) return
    select case (word)
    case ('YES')
      body%release = .true.
    case ('NO')
      body%release = .false.
    case default
      call card_error(error, cards, card, 'RELEASE must be YES or NO, got "'//word//'"', &
                      field_column(card, 'RELEASE')); return
    end select
    call check_fields_used(cards, card, error, form); if (allocated(error)) return
    body%line = card%line
  end subroutine read_body

  !> PAD THICKNESS=.. MAT=id [WIDTH=..] [SIZE=..] [BOTTOM=BONDED|SLIP].
  subroutine read_pad(cards, card, pad, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(pad_t), intent(inout) :: pad
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word
    character(len=*), parameter :: form = 'PAD THICKNESS=.. MAT=id [COVER=.. COVERMAT=id] [WIDTH=..] [SIZE=..] '// &
                                          '[BOTTOM=BONDED|SLIP]'
    if (.not. has_field(card, 'THICKNESS')) then
      call card_error(error, cards, card, 'missing field THICKNESS= (expected: '//form//')'); return
    end if
    if (.not. has_field(card, 'MAT')) then
      call card_error(error, cards, card, 'missing field MAT= (the pad''s material; expected: '//form//')'); return
    end if
    call named_real(cards, card, 'THICKNESS', pad%thickness, error, range=pad_length_range)
    if (allocated(error)) return
    call named_real(cards, card, 'WIDTH', pad%width, error, default=0.0_dp, range=pad_length_range)
    if (allocated(error)) return
    call named_real(cards, card, 'SIZE', pad%size, error, default=0.0_dp, range=pad_length_range)
    if (allocated(error)) return
    call named_word(cards, card, 'MAT', pad%material, error); if (allocated(error)) return
    if (len(pad%material) > 32) then
      call card_error(error, cards, card, 'MAT id longer than 32 characters', field_column(card, 'MAT')); return
    end if
    call named_real(cards, card, 'COVER', pad%cover, error, default=0.0_dp, range=pad_length_range)
    if (allocated(error)) return
    call named_word(cards, card, 'COVERMAT', pad%cover_material, error, default=''); if (allocated(error)) return
    if (has_field(card, 'COVER') .neqv. has_field(card, 'COVERMAT')) then
      call card_error(error, cards, card, 'COVER= (the top layer''s thickness) and COVERMAT= (its material) go '// &
        'together', field_column(card, trim(merge('COVER   ', 'COVERMAT', has_field(card, 'COVER'))))); return
    end if
    if (len(pad%cover_material) > 32) then
      call card_error(error, cards, card, 'COVERMAT id longer than 32 characters', field_column(card, 'COVERMAT'))
      return
    end if
    if (pad%cover >= pad%thickness) then
      call card_error(error, cards, card, 'COVER must be less than THICKNESS (the cover lies within the pad), got '// &
        'COVER = '//short_real(pad%cover)//' m, THICKNESS = '//short_real(pad%thickness)//' m', &
        field_column(card, 'COVER')); return
    end if
    call named_word(cards, card, 'BOTTOM', word, error, default='BONDED'); if (allocated(error)) return
    select case (word)
    case ('BONDED')
      pad%bonded = .true.
    case ('SLIP')
      pad%bonded = .false.
    case default
      call card_error(error, cards, card, 'BOTTOM must be BONDED or SLIP, got "'//word//'"', &
                      field_column(card, 'BOTTOM')); return
    end select
    call check_fields_used(cards, card, error, form); if (allocated(error)) return
    pad%line = card%line
  end subroutine read_pad

  !> Name of a stop criterion as written on the STOP card.
  pure function stop_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    select case (code)
    case (stop_at_max_deformation); name = 'MAXDEFORMATION'
    case (stop_at_separation); name = 'SEPARATION'
    case default; name = 'TEND'
    end select
  end function stop_name

  !> PLATE Z=0 [STICK | SLIP] [RELEASE=YES|NO].
  subroutine read_plate(cards, card, plate, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(plate_t), intent(inout) :: plate
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word
    character(len=*), parameter :: form = 'PLATE Z=.. [STICK | SLIP] [RELEASE=YES|NO]'
    call named_real(cards, card, 'Z', plate%z, error, range=length_range); if (allocated(error)) return
    call positional_word(cards, card, 1, 'contact kind (STICK or SLIP)', word, error, optional_field=.true.)
    if (allocated(error)) return
    select case (word)
    case ('', 'STICK')
      plate%stick = .true.
    case ('SLIP')
      plate%stick = .false.
    case default
      call card_error(error, cards, card, 'contact kind must be STICK or SLIP, got "'//word//'"', &
                      field_column(card, '1')); return
    end select
    call named_word(cards, card, 'RELEASE', word, error, default='NO'); if (allocated(error)) return
    select case (word)
    case ('YES')
      plate%release = .true.
    case ('NO')
      plate%release = .false.
    case default
      call card_error(error, cards, card, 'RELEASE must be YES or NO, got "'//word//'"', &
                      field_column(card, 'RELEASE')); return
    end select
    call check_fields_used(cards, card, error, form); if (allocated(error)) return
    plate%line = card%line
  end subroutine read_plate

  !> STOP AT=MAXDEFORMATION | SEPARATION | TEND.
  subroutine read_stop(cards, card, stop_at, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    integer, intent(out) :: stop_at
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word
    character(len=*), parameter :: form = 'STOP AT=MAXDEFORMATION | SEPARATION | TEND'
    if (.not. has_field(card, 'AT')) then
      call card_error(error, cards, card, 'missing field AT= (expected: '//form//')'); return
    end if
    call named_word(cards, card, 'AT', word, error); if (allocated(error)) return
    call check_fields_used(cards, card, error, form)
    if (allocated(error)) return
    select case (word)
    case ('MAXDEFORMATION')
      stop_at = stop_at_max_deformation
    case ('SEPARATION')
      stop_at = stop_at_separation
    case ('TEND')
      stop_at = stop_at_tend
    case default
      call card_error(error, cards, card, 'AT must be MAXDEFORMATION, SEPARATION or TEND, got "'//word//'"', &
                      field_column(card, 'AT'))
    end select
  end subroutine read_stop
end module visco2d_contact_cards
