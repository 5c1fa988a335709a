!> The cards of the contact extension: PLATE (a rigid flat plate) and STOP
!> (when a dynamic run ends). Each reader checks its own card; visco2d_deck
!> checks how the cards fit together.
module visco2d_contact_cards
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_ranges, only: length_range
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_word, positional_word, &
                           check_fields_used, has_field, field_column
  implicit none
  private

  public :: plate_t, read_plate, read_stop, stop_name
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

contains

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
