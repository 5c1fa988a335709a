!> The BRUISE card: a failure criterion and its threshold for the flesh of a
!> material (bruise prediction). The reader checks its own card; the deck
!> reader checks how the BRUISE cards fit together (one per material).
!>
!>     BRUISE CRITERION=MAXSHEAR STRESS=0.3e6 [MAT=FLESH] [THRESHOLDS=0.2e6,0.4e6]
!>     BRUISE CRITERION=ENERGY ENERGY=5e4 [MAT=FLESH] [THRESHOLDS=4e4,6e4]
!>
!> No literature value is assumed: the user gives the threshold.
module visco2d_bruise_cards
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_material, only: material_t
  use visco2d_strings, only: short_real, integer_text
  use visco2d_ranges, only: range_t, in_range, range_text, failure_stress_range, failure_energy_range, plastic_strain_range
  use visco2d_card_lists, only: read_increasing_list
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_word, has_field, &
                           check_fields_used, field_column, parse_real
  implicit none
  private

  public :: bruise_card_t, read_bruise, check_bruise_cards, criterion_name, criterion_unit
  public :: criterion_max_shear, criterion_mises, criterion_octahedral, criterion_energy, criterion_plastic

  integer, parameter :: criterion_max_shear = 1   !< Tresca: (sigma_1 - sigma_3)/2, Pa
  integer, parameter :: criterion_mises = 2       !< von Mises equivalent stress, Pa
  integer, parameter :: criterion_octahedral = 3  !< octahedral shear stress sqrt(2)/3 sigma_Mises, Pa
  integer, parameter :: criterion_energy = 4      !< strain-energy density, J/m^3
  integer, parameter :: criterion_plastic = 5     !< equivalent plastic strain (a PLASTIC material): failed flesh

  !> One BRUISE card: the flesh of material `material` (all materials if '')
  !> is bruised where the time envelope of the criterion reaches `threshold`.
  type :: bruise_card_t
    integer :: criterion = criterion_max_shear
    real(dp) :: threshold = 0.0_dp             !< Pa (stress criteria), J/m^3 (ENERGY) or 1 (PLASTIC, exceeded)
    real(dp), allocatable :: extra(:)          !< THRESHOLDS=: more thresholds, same unit, increasing
    character(:), allocatable :: material      !< MAT= id (upper case); '' for every material
    integer :: line = 0
    integer :: column = 0                      !< column of the card's keyword
    integer :: material_column = 0             !< column of MAT= (0: none), for errors
  end type bruise_card_t

contains

  !> The criterion as written on the card.
  pure function criterion_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    select case (code)
    case (criterion_mises); name = 'MISES'
    case (criterion_octahedral); name = 'OCTAHEDRAL'
    case (criterion_energy); name = 'ENERGY'
    case (criterion_plastic); name = 'PLASTIC'
    case default; name = 'MAXSHEAR'
    end select
  end function criterion_name

  !> Unit of the criterion's value: 'Pa', 'J/m^3' or '1' (a strain).
  pure function criterion_unit(code) result(unit)
    integer, intent(in) :: code
    character(:), allocatable :: unit
    if (code == criterion_energy) then
      unit = 'J/m^3'
    else if (code == criterion_plastic) then
      unit = '1'
    else
      unit = 'Pa'
    end if
  end function criterion_unit

  !> BRUISE CRITERION=MAXSHEAR|MISES|OCTAHEDRAL STRESS=.. | CRITERION=ENERGY ENERGY=..
  !> | CRITERION=PLASTIC [STRAIN=0] [MAT=id] [THRESHOLDS=v1,v2,...], appended to `bruises`.
  !> PLASTIC: the flesh is bruised (failed) where its equivalent plastic strain
  !> exceeds STRAIN (default 0: wherever it yielded).
  subroutine read_bruise(cards, card, bruises, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(bruise_card_t), allocatable, intent(inout) :: bruises(:)
    type(error_t), allocatable, intent(inout) :: error
    type(bruise_card_t) :: bruise
    character(:), allocatable :: word, value_field
    type(range_t) :: range
    character(len=*), parameter :: form = 'BRUISE CRITERION=MAXSHEAR|MISES|OCTAHEDRAL STRESS=<Pa> '// &
      '(or CRITERION=ENERGY ENERGY=<J/m^3>, or CRITERION=PLASTIC [STRAIN=0]) [MAT=id] [THRESHOLDS=v1,v2,...]'
    if (.not. has_field(card, 'CRITERION')) then
      call card_error(error, cards, card, 'missing field CRITERION= (expected: '//form//')'); return
    end if
    call named_word(cards, card, 'CRITERION', word, error); if (allocated(error)) return
    select case (word)
    case ('MAXSHEAR'); bruise%criterion = criterion_max_shear
    case ('MISES'); bruise%criterion = criterion_mises
    case ('OCTAHEDRAL'); bruise%criterion = criterion_octahedral
    case ('ENERGY'); bruise%criterion = criterion_energy
    case ('PLASTIC'); bruise%criterion = criterion_plastic
    case default
      call card_error(error, cards, card, 'CRITERION must be MAXSHEAR, MISES, OCTAHEDRAL, ENERGY or PLASTIC, got "'// &
                      word//'"', field_column(card, 'CRITERION')); return
    end select
    if (bruise%criterion == criterion_plastic) then
      value_field = 'STRAIN'
      range = plastic_strain_range
      if (has_field(card, 'STRESS') .or. has_field(card, 'ENERGY')) then
        call card_error(error, cards, card, 'CRITERION=PLASTIC takes its threshold as STRAIN=<equivalent plastic '// &
                        'strain> (default 0), not STRESS= or ENERGY=', max(field_column(card, 'STRESS'), &
                        field_column(card, 'ENERGY'))); return
      end if
    else if (bruise%criterion == criterion_energy) then
      value_field = 'ENERGY'
      range = failure_energy_range
      if (has_field(card, 'STRESS')) then
        call card_error(error, cards, card, 'CRITERION=ENERGY takes its threshold as ENERGY=<J/m^3>, not STRESS=', &
                        field_column(card, 'STRESS')); return
      end if
    else
      value_field = 'STRESS'
      range = failure_stress_range
      if (has_field(card, 'ENERGY')) then
        call card_error(error, cards, card, 'CRITERION='//word//' takes its threshold as STRESS=<Pa>, not ENERGY=', &
                        field_column(card, 'ENERGY')); return
      end if
    end if
    if (.not. has_field(card, value_field) .and. bruise%criterion /= criterion_plastic) then
      call card_error(error, cards, card, 'missing field '//value_field//'= (the failure threshold in '// &
                      criterion_unit(bruise%criterion)//'; no default is assumed)'); return
    end if
    call named_real(cards, card, value_field, bruise%threshold, error, range=range, default=0.0_dp)
    if (allocated(error)) return
    call named_word(cards, card, 'MAT', bruise%material, error, default=''); if (allocated(error)) return
    if (len(bruise%material) > 0) bruise%material_column = field_column(card, 'MAT')
    call named_word(cards, card, 'THRESHOLDS', word, error, default=''); if (allocated(error)) return
    call check_fields_used(cards, card, error, form); if (allocated(error)) return
    call read_thresholds(word); if (allocated(error)) return
    bruise%line = card%line
    bruise%column = card%column
    bruises = [bruises, bruise]

  contains

    !> THRESHOLDS=v1,v2,...: increasing values in the criterion's range.
    subroutine read_thresholds(list)
      character(*), intent(in) :: list
      call read_increasing_list(cards, card, 'THRESHOLDS', list, 'numbers in '//criterion_unit(bruise%criterion), &
                                'values', range, bruise%extra, error)
    end subroutine read_thresholds
  end subroutine read_bruise

  !> The BRUISE cards together: each MAT= names a material of the deck, at
  !> most one card per material and at most one without MAT=; QUASISTATIC runs
  !> keep no envelopes (BRUISE belongs to STATIC and DYNAMIC).
  subroutine check_bruise_cards(cards, bruises, materials, quasistatic, error)
    type(card_deck_t), intent(in) :: cards
    type(bruise_card_t), intent(in) :: bruises(:)
    type(material_t), intent(in) :: materials(:)
    logical, intent(in) :: quasistatic
    type(error_t), allocatable, intent(inout) :: error
    integer :: i, j
    do i = 1, size(bruises)
      associate (b => bruises(i))
      if (quasistatic) then
        call set_error(error, 'BRUISE needs ANALYSIS STATIC or DYNAMIC (a QUASISTATIC run keeps no stress '// &
                       'envelopes)', file=cards%file, line=b%line, column=b%column, card='BRUISE'); return
      end if
      if (len(b%material) > 0) then
        if (.not. any([(materials(j)%id == b%material, j = 1, size(materials))])) then
          call set_error(error, 'MAT='//b%material//' is not defined by a MATERIAL card', file=cards%file, &
                         line=b%line, column=b%material_column, card='BRUISE'); return
        end if
      end if
      do j = 1, i - 1
        if (bruises(j)%material == b%material) then
          if (len(b%material) > 0) then
            call set_error(error, 'a second BRUISE card for material '//b%material//' (the first is on line '// &
                           integer_text(bruises(j)%line)//')', file=cards%file, line=b%line, column=b%material_column, &
                           card='BRUISE')
          else
            call set_error(error, 'a second BRUISE card without MAT= (the first is on line '// &
                           integer_text(bruises(j)%line)//'); give MAT=<id> to set a criterion per material', &
                           file=cards%file, line=b%line, column=b%column, card='BRUISE')
          end if
          return
        end if
      end do
      end associate
    end do
  end subroutine check_bruise_cards
end module visco2d_bruise_cards
