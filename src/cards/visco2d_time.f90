!> The time axis of a quasi-static or dynamic run: TIME cards, each a
!> stage of constant steps that starts where the previous one ended
!> (time_stage_t, of visco2d_model).
module visco2d_time
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_ranges, only: time_step_range, time_range
  use visco2d_error, only: error_t
  use visco2d_strings, only: integer_text, short_real
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, check_fields_used, field_column
  use visco2d_model, only: time_stage_t
  implicit none
  private

  public :: time_stage_t, read_time, max_steps

  !> Most steps a deck may ask for (a guard against a mistyped DT).
  integer, parameter :: max_steps = 10000000

contains

  !> TIME DT=.. TEND=..: one stage of constant steps; several TIME cards follow each other in time.
  !> DT within time_step_range and at most the stage's length; TEND after the
  !> previous stage's end and within time_range; at most max_steps in all.
  subroutine read_time(cards, card, stages, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(time_stage_t), allocatable, intent(inout) :: stages(:)
    type(error_t), allocatable, intent(inout) :: error
    type(time_stage_t) :: stage
    real(dp) :: start, requested, length
    integer(int64) :: steps, total
    integer :: k
    call named_real(cards, card, 'DT', requested, error, range=time_step_range); if (allocated(error)) return
    call named_real(cards, card, 'TEND', stage%end_time, error, range=time_range); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'TIME DT=.. TEND=..'); if (allocated(error)) return
    start = 0.0_dp
    if (size(stages) > 0) start = stages(size(stages))%end_time
    if (stage%end_time <= start) then
      call card_error(error, cards, card, 'TEND must be after the start of this stage ('//short_real(start)// &
                      ' s), got '//short_real(stage%end_time), field_column(card, 'TEND')); return
    end if
    length = stage%end_time - start
    if (requested > length*(1.0_dp + 1.0e-9_dp)) then
      call card_error(error, cards, card, 'DT = '//short_real(requested)//' s is longer than the stage it steps '// &
                      'through ('//short_real(start)//' s to TEND = '//short_real(stage%end_time)//' s, '// &
                      short_real(length)//' s)', field_column(card, 'DT')); return
    end if
    ! Whole steps: DT is shortened (never lengthened) to end exactly at TEND.
    ! length/requested <= 1e9/1e-12: no overflow; the count is checked before it becomes an integer.
    if (length/requested > real(max_steps, dp)) then
      call card_error(error, cards, card, 'DT = '//short_real(requested)//' s would take more than '// &
                      integer_text(max_steps)//' steps to reach TEND', field_column(card, 'DT')); return
    end if
    stage%steps = max(1, ceiling(length/requested*(1.0_dp - 1.0e-12_dp)))
    stage%dt = length/stage%steps
    stage%line = card%line
    total = stage%steps
    do k = 1, size(stages)
      total = total + int(stages(k)%steps, int64)
    end do
    if (total > max_steps) then
      steps = total - stage%steps
      call card_error(error, cards, card, 'the TIME stages add up to '//integer_text(total)//' steps, more than '// &
                      integer_text(max_steps)//' (the stages before this one take '//integer_text(steps)//')', &
                      field_column(card, 'DT')); return
    end if
    stages = [stages, stage]
  end subroutine read_time

end module visco2d_time
