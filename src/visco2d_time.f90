!> The time axis of a quasi-static (and later dynamic) run: TIME cards, each a
!> stage of constant steps that starts where the previous one ended.
module visco2d_time
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_strings, only: itoa, short_real
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, check_fields_used, field_column
  implicit none
  private

  public :: time_stage_t, read_time, max_steps

  !> Most steps a deck may ask for (a guard against a mistyped DT).
  integer, parameter :: max_steps = 10000000

  !> A stage of the time axis: constant steps dt from the previous stage's end to end_time.
  type :: time_stage_t
    real(dp) :: dt = 0.0_dp        !< s (as used: (end - start)/steps)
    real(dp) :: end_time = 0.0_dp  !< s
    integer :: steps = 0
    integer :: line = 0
  end type time_stage_t

contains

  !> TIME DT=.. TEND=..: one stage of constant steps; several TIME cards follow each other in time.
  subroutine read_time(cards, card, stages, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(time_stage_t), allocatable, intent(inout) :: stages(:)
    type(error_t), allocatable, intent(inout) :: error
    type(time_stage_t) :: stage
    real(dp) :: start, requested
    call named_real(cards, card, 'DT', requested, error); if (allocated(error)) return
    call named_real(cards, card, 'TEND', stage%end_time, error); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'TIME DT=.. TEND=..'); if (allocated(error)) return
    if (requested <= 0.0_dp) then
      call card_error(error, cards, card, 'DT must be > 0 s, got '//short_real(requested), field_column(card, 'DT'))
      return
    end if
    start = 0.0_dp
    if (size(stages) > 0) start = stages(size(stages))%end_time
    if (stage%end_time <= start) then
      call card_error(error, cards, card, 'TEND must be after the start of this stage ('//short_real(start)// &
                      ' s), got '//short_real(stage%end_time), field_column(card, 'TEND')); return
    end if
    ! Whole steps: DT is shortened (never lengthened) to end exactly at TEND.
    if ((stage%end_time - start)/requested > real(max_steps, dp)) then
      call card_error(error, cards, card, 'DT = '//short_real(requested)//' s would take more than '// &
                      itoa(max_steps)//' steps to reach TEND', field_column(card, 'DT')); return
    end if
    stage%steps = max(1, ceiling((stage%end_time - start)/requested*(1.0_dp - 1.0e-12_dp)))
    stage%dt = (stage%end_time - start)/stage%steps
    stage%line = card%line
    stages = [stages, stage]
    if (sum(stages%steps) > max_steps) then
      call card_error(error, cards, card, 'the TIME stages add up to more than '//itoa(max_steps)//' steps')
    end if
  end subroutine read_time
end module visco2d_time
