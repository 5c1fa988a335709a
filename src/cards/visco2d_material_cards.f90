!> The MATERIAL and PRONY cards: elastic, viscoelastic (shear Prony series,
!> eq. [12]) and uniaxial (eq. [47], converted exactly by eq. [48]) materials,
!> completed once all their PRONY cards are read; the PLASTIC and HARDENING
!> cards of a material's von Mises plasticity (its hardening curve: bilinear,
!> PLASTIC YIELD= TANGENT=, or tabulated, PLASTIC TABLE [SLOPE=] and
!> HARDENING STRAIN= STRESS= points).
module visco2d_material_cards
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_strings, only: short_real, message_real, integer_text, compact_real
  use visco2d_ranges, only: modulus_range, density_range, rate_range, bulk_shear_ratio_limit, &
                            failure_stress_range, plastic_strain_range, hardening_slope_range
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, positional_word, check_fields_used, &
                           has_field, field_column, positional_count
  use visco2d_material, only: material_t, material_kind_elastic, material_kind_viscoelastic, &
                              material_kind_uniaxial, elastic_constants_from_e_nu, bilinear_hardening, &
                              hyperelastic_neo_hooke, hyperelastic_mooney_rivlin, hyperelastic_foam
  use visco2d_relaxation, only: uniaxial_to_shear
  use visco2d_sorting, only: sorted_order
  implicit none
  private

  public :: read_material, read_prony, finish_material, read_plastic, read_hardening, read_ogden

contains

  !> MATERIAL id ELASTIC E=.. NU=.. [RHO=..]   or   MATERIAL id ELASTIC G=.. K=.. [RHO=..]
  !> MATERIAL id VISCOELASTIC K=.. [RHO=..]      followed by PRONY G=.. BETA=.. cards
  !> MATERIAL id UNIAXIAL NU=.. [RHO=..]         followed by PRONY E=.. ALPHA=.. cards
  !> MATERIAL id NEOHOOKE C10=.. D1=.. [RHO=..]  or E=.. NU=.. or G=.. K=.. (W = C10 (I1bar - 3) + (J - 1)^2 / D1)
  !> MATERIAL id MOONEY C10=.. C01=.. D1=.. [RHO=..]
  !> MATERIAL id HYPERFOAM [RHO=..]             followed by OGDEN MU=.. ALPHA=.. NU=.. cards (1 to 6)
  subroutine read_material(cards, card, materials, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(material_t), allocatable, intent(inout) :: materials(:)
    type(error_t), allocatable, intent(inout) :: error
    type(material_t) :: material
    character(:), allocatable :: kind
    integer :: k
    call positional_word(cards, card, 1, 'material id', material%id, error); if (allocated(error)) return
    call positional_word(cards, card, 2, 'material kind (ELASTIC, VISCOELASTIC, UNIAXIAL, NEOHOOKE, MOONEY or '// &
                         'HYPERFOAM)', kind, error)
    if (allocated(error)) return
    material%line = card%line
    do k = 1, size(materials)
      if (materials(k)%id == material%id) then
        call field_error('material '//material%id//' defined twice (first on line '//integer_text(materials(k)%line)//')', &
                         '1'); return
      end if
    end do
    call named_real(cards, card, 'RHO', material%density, error, default=0.0_dp, range=density_range)
    if (allocated(error)) return
    select case (kind)
    case ('ELASTIC')
      material%kind = material_kind_elastic
      if ((has_field(card, 'E') .or. has_field(card, 'NU')) .and. (has_field(card, 'G') .or. has_field(card, 'K'))) then
        call field_error('give the elastic constants one way: E= and NU=, or G= and K= (this card mixes them: '// &
          'two constants fix an isotropic material, a third would contradict them)', &
          trim(merge('G', 'K', has_field(card, 'G')))); return
      end if
      if (has_field(card, 'E') .or. has_field(card, 'NU')) then
        call named_real(cards, card, 'E', material%young, error, range=modulus_range); if (allocated(error)) return
        call named_real(cards, card, 'NU', material%poisson, error); if (allocated(error)) return
        if (material%poisson <= -1.0_dp .or. material%poisson >= 0.5_dp) then
          call field_error('NU must be in (-1, 0.5), got '//short_real(material%poisson), 'NU'); return
        end if
        call elastic_constants_from_e_nu(material%young, material%poisson, material%shear, material%bulk)
        if (.not. conditioned(material)) then
          call field_error(ratio_message(material), 'NU'); return
        end if
      else
        call named_real(cards, card, 'G', material%shear, error, range=modulus_range); if (allocated(error)) return
        call named_real(cards, card, 'K', material%bulk, error, range=modulus_range); if (allocated(error)) return
        call instantaneous_e_nu(material)
        if (.not. conditioned(material)) then
          call field_error(ratio_message(material), 'K'); return
        end if
      end if
      material%long_term_shear = material%shear
      call check_fields_used(cards, card, error, 'MATERIAL id ELASTIC E=.. NU=.. [RHO=..] or G=.. K=.. [RHO=..]')
      if (allocated(error)) return
    case ('VISCOELASTIC')
      material%kind = material_kind_viscoelastic
      call named_real(cards, card, 'K', material%bulk, error, range=modulus_range); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'MATERIAL id VISCOELASTIC K=.. [RHO=..], then PRONY G=.. BETA=..')
      if (allocated(error)) return
      allocate(material%prony_shear(0), material%prony_rate(0), material%prony_lines(0))
    case ('UNIAXIAL')
      material%kind = material_kind_uniaxial
      call named_real(cards, card, 'NU', material%poisson, error); if (allocated(error)) return
      if (material%poisson <= -1.0_dp .or. material%poisson >= 0.5_dp) then
        call field_error('NU must be in (-1, 0.5), got '//short_real(material%poisson), 'NU'); return
      end if
      call check_fields_used(cards, card, error, 'MATERIAL id UNIAXIAL NU=.. [RHO=..], then PRONY E=.. ALPHA=..')
      if (allocated(error)) return
      allocate(material%uniaxial_young(0), material%uniaxial_rate(0), material%prony_lines(0))
    case ('NEOHOOKE', 'MOONEY')
      call read_hyperelastic(); if (allocated(error)) return
    case ('HYPERFOAM')
      material%kind = material_kind_elastic
      material%hyperelastic = hyperelastic_foam
      allocate(material%foam_mu(0), material%foam_alpha(0), material%foam_nu(0), material%foam_lines(0))
      call check_fields_used(cards, card, error, 'MATERIAL id HYPERFOAM [RHO=..], then OGDEN MU=.. ALPHA=.. NU=..')
      if (allocated(error)) return
    case default
      call card_error(error, cards, card, 'material kind must be ELASTIC, VISCOELASTIC, UNIAXIAL, NEOHOOKE, '// &
                      'MOONEY or HYPERFOAM, got "'//kind//'"', field_column(card, '2')); return
    end select
    material%card_column = field_column(card, 'K')
    if (material%kind == material_kind_uniaxial) material%card_column = field_column(card, 'NU')
    materials = [materials, material]
  contains
    subroutine field_error(message, name)
      character(*), intent(in) :: message
      character(*), intent(in), optional :: name
      integer :: column
      column = card%column
      if (present(name)) column = field_column(card, name)
      call card_error(error, cards, card, message, column)
    end subroutine field_error

    !> NEOHOOKE (C10= D1=, or E= NU=, or G= K=) and MOONEY (C10= C01= D1=):
    !> the constants of W and the small-strain moduli G = 2 (C10 + C01), K = 2 / D1.
    subroutine read_hyperelastic()
      character(:), allocatable :: usage
      material%kind = material_kind_elastic
      if (kind == 'NEOHOOKE') then
        material%hyperelastic = hyperelastic_neo_hooke
        usage = 'MATERIAL id NEOHOOKE C10=.. D1=.. [RHO=..] or E=.. NU=.. or G=.. K=..'
        if (count([has_field(card, 'C10') .or. has_field(card, 'D1'), has_field(card, 'E') .or. &
                   has_field(card, 'NU'), has_field(card, 'G') .or. has_field(card, 'K')]) > 1) then
          call field_error('give the neo-Hookean constants one way: C10= and D1=, E= and NU=, or G= and K= (two '// &
                           'constants fix the law)'); return
        end if
        if (has_field(card, 'E') .or. has_field(card, 'NU')) then
          call named_real(cards, card, 'E', material%young, error, range=modulus_range); if (allocated(error)) return
          call named_real(cards, card, 'NU', material%poisson, error); if (allocated(error)) return
          if (material%poisson <= -1.0_dp .or. material%poisson >= 0.5_dp) then
            call field_error('NU must be in (-1, 0.5), got '//short_real(material%poisson), 'NU'); return
          end if
          call elastic_constants_from_e_nu(material%young, material%poisson, material%shear, material%bulk)
          material%c10 = 0.5_dp*material%shear
          material%d1 = 2.0_dp/material%bulk
        else if (has_field(card, 'G') .or. has_field(card, 'K')) then
          call named_real(cards, card, 'G', material%shear, error, range=modulus_range); if (allocated(error)) return
          call named_real(cards, card, 'K', material%bulk, error, range=modulus_range); if (allocated(error)) return
          material%c10 = 0.5_dp*material%shear
          material%d1 = 2.0_dp/material%bulk
        else
          call named_real(cards, card, 'C10', material%c10, error, range=modulus_range); if (allocated(error)) return
          call read_d1(); if (allocated(error)) return
        end if
      else
        material%hyperelastic = hyperelastic_mooney_rivlin
        usage = 'MATERIAL id MOONEY C10=.. C01=.. D1=.. [RHO=..]'
        call named_real(cards, card, 'C10', material%c10, error); if (allocated(error)) return
        call named_real(cards, card, 'C01', material%c01, error); if (allocated(error)) return
        if (material%c10 + material%c01 <= 0.0_dp .or. material%c10 < 0.0_dp .or. material%c01 < 0.0_dp) then
          call field_error('C10 and C01 must be >= 0 with C10 + C01 > 0 (the initial shear modulus is '// &
                           '2 (C10 + C01)), got C10 = '//short_real(material%c10)//', C01 = '// &
                           short_real(material%c01), 'C01'); return
        end if
        call read_d1(); if (allocated(error)) return
      end if
      material%shear = 2.0_dp*(material%c10 + material%c01)
      material%bulk = 2.0_dp/material%d1
      call instantaneous_e_nu(material)
      if (.not. conditioned(material)) then
        call field_error(ratio_message(material)); return
      end if
      material%long_term_shear = material%shear
      call check_fields_used(cards, card, error, usage)
    end subroutine read_hyperelastic

    !> D1 = 2 / K, 1/Pa, > 0.
    subroutine read_d1()
      call named_real(cards, card, 'D1', material%d1, error); if (allocated(error)) return
      if (.not. (material%d1 > 0.0_dp) .or. material%d1 > 1.0_dp) then
        call field_error('D1 (= 2/K, 1/Pa) must be in (0, 1], got '//short_real(material%d1), 'D1'); return
      end if
    end subroutine read_d1
  end subroutine read_material

  !> OGDEN MU=.. ALPHA=.. NU=..: one term of a HYPERFOAM material (ABAQUS'
  !> *HYPERFOAM mu_i, alpha_i, nu_i): W gains 2 mu / alpha^2 (lambda1^alpha +
  !> lambda2^alpha + lambda3^alpha - 3 + (J^(-alpha beta) - 1)/beta), beta = nu/(1 - 2 nu).
  subroutine read_ogden(cards, card, material, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: mu, alpha, nu
    if (material%hyperelastic /= hyperelastic_foam) then
      call card_error(error, cards, card, 'OGDEN terms belong to a HYPERFOAM material; material '//material%id// &
                      ' is not one'); return
    end if
    if (size(material%foam_mu) >= 6) then
      call card_error(error, cards, card, 'a HYPERFOAM material takes at most 6 OGDEN terms (as ABAQUS'' N <= 6)')
      return
    end if
    call named_real(cards, card, 'MU', mu, error); if (allocated(error)) return
    call named_real(cards, card, 'ALPHA', alpha, error); if (allocated(error)) return
    call named_real(cards, card, 'NU', nu, error); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'OGDEN MU=.. ALPHA=.. NU=.. after MATERIAL id HYPERFOAM')
    if (allocated(error)) return
    if (.not. (abs(mu) > 0.0_dp .and. abs(mu) < 1.0e12_dp)) then
      call card_error(error, cards, card, 'MU must be nonzero and below 1e12 Pa in magnitude, got '//short_real(mu), &
                      field_column(card, 'MU')); return
    end if
    if (.not. (abs(alpha) >= 1.0e-3_dp .and. abs(alpha) <= 100.0_dp)) then
      call card_error(error, cards, card, 'ALPHA must be nonzero, 1e-3 <= |ALPHA| <= 100, got '//short_real(alpha), &
                      field_column(card, 'ALPHA')); return
    end if
    if (.not. (nu > -1.0_dp .and. nu < 0.5_dp)) then
      call card_error(error, cards, card, 'NU must be in (-1, 0.5), got '//short_real(nu), field_column(card, 'NU'))
      return
    end if
    material%foam_mu = [material%foam_mu, mu]
    material%foam_alpha = [material%foam_alpha, alpha]
    material%foam_nu = [material%foam_nu, nu]
    material%foam_lines = [material%foam_lines, card%line]
  end subroutine read_ogden

  !> PRONY G=.. BETA=.. (VISCOELASTIC) or PRONY E=.. ALPHA=.. (UNIAXIAL): one term of eq. [12] or [47].
  subroutine read_prony(cards, card, material, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: modulus, rate
    select case (material%kind)
    case (material_kind_viscoelastic)
      call named_real(cards, card, 'G', modulus, error, range=modulus_range); if (allocated(error)) return
      call named_real(cards, card, 'BETA', rate, error, range=rate_range); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'PRONY G=.. BETA=.. after MATERIAL id VISCOELASTIC')
      if (allocated(error)) return
      call check_new_rate(material%prony_rate, 'BETA', 'G'); if (allocated(error)) return
      material%prony_shear = [material%prony_shear, modulus]
      material%prony_rate = [material%prony_rate, rate]
      material%prony_lines = [material%prony_lines, card%line]
    case (material_kind_uniaxial)
      call named_real(cards, card, 'E', modulus, error, range=modulus_range); if (allocated(error)) return
      call named_real(cards, card, 'ALPHA', rate, error, range=rate_range); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'PRONY E=.. ALPHA=.. after MATERIAL id UNIAXIAL')
      if (allocated(error)) return
      call check_new_rate(material%uniaxial_rate, 'ALPHA', 'E'); if (allocated(error)) return
      material%uniaxial_young = [material%uniaxial_young, modulus]
      material%uniaxial_rate = [material%uniaxial_rate, rate]
      material%prony_lines = [material%prony_lines, card%line]
    case default
      call card_error(error, cards, card, 'PRONY terms belong to a VISCOELASTIC or UNIAXIAL material; material '// &
                      material%id//' is ELASTIC')
    end select
  contains
    !> One term per rate: a second term with the same rate (a duplicated
    !> line?) would silently add to the first.
    subroutine check_new_rate(rates, rate_name, modulus_name)
      real(dp), intent(in) :: rates(:)
      character(*), intent(in) :: rate_name, modulus_name
      integer :: k
      do k = 1, size(rates)
        if (rates(k) /= rate) cycle
        call card_error(error, cards, card, 'material '//material%id//' already has a term with '//rate_name//' = '// &
          short_real(rate)//' 1/s (line '//integer_text(material%prony_lines(k))//'): give one term per rate, with the '// &
          'sum of their '//modulus_name, field_column(card, rate_name))
        return
      end do
    end subroutine check_new_rate
  end subroutine read_prony

  !> PLASTIC YIELD=Y TANGENT=Et (the bilinear curve: H = E Et / (E - Et),
  !> E the instantaneous Young's modulus, set by finish_material) or
  !> PLASTIC TABLE [SLOPE=H] followed by HARDENING cards: the von Mises
  !> plasticity of the material whose cards it follows.
  subroutine read_plastic(cards, card, material, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word
    if (material%plastic) then
      call card_error(error, cards, card, 'material '//material%id//' already has a PLASTIC card (line '// &
                      integer_text(material%plastic_line)//'): give one per material'); return
    end if
    material%plastic = .true.
    material%plastic_line = card%line
    if (positional_count(card) > 0) then
      call positional_word(cards, card, 1, 'TABLE', word, error); if (allocated(error)) return
      if (word /= 'TABLE') then
        call card_error(error, cards, card, 'PLASTIC takes YIELD=.. TANGENT=.. (a bilinear curve) or the word '// &
                        'TABLE (then HARDENING cards), got "'//word//'"', field_column(card, '1')); return
      end if
      material%plastic_table = .true.
      material%plastic_column = field_column(card, '1')
      call named_real(cards, card, 'SLOPE', material%hardening%final_slope, error, default=0.0_dp, &
                      range=hardening_slope_range); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'PLASTIC TABLE [SLOPE=..], then HARDENING STRAIN=.. STRESS=..')
      if (allocated(error)) return
      allocate(material%hardening%plastic_strain(0), material%hardening%stress(0))
    else
      call named_real(cards, card, 'YIELD', material%plastic_yield, error, range=failure_stress_range)
      if (allocated(error)) return
      call named_real(cards, card, 'TANGENT', material%plastic_tangent, error, range=hardening_slope_range)
      if (allocated(error)) return
      material%plastic_column = field_column(card, 'TANGENT')
      call check_fields_used(cards, card, error, 'PLASTIC YIELD=.. TANGENT=.. or PLASTIC TABLE [SLOPE=..]')
    end if
  end subroutine read_plastic

  !> HARDENING STRAIN=ebar STRESS=sigma_y: one point of a PLASTIC TABLE's
  !> curve. The first is the initial yield (STRAIN=0); the strains increase
  !> and the stresses do not decrease (no softening: a softening material
  !> localizes in one row of elements, its answer the mesh's).
  subroutine read_hardening(cards, card, material, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: strain, stress
    integer :: n
    if (.not. material%plastic_table) then
      call card_error(error, cards, card, 'HARDENING points belong to a PLASTIC TABLE card; the PLASTIC card of '// &
                      'material '//material%id//' (line '//integer_text(material%plastic_line)//') gives YIELD= TANGENT='); return
    end if
    call named_real(cards, card, 'STRAIN', strain, error, range=plastic_strain_range); if (allocated(error)) return
    call named_real(cards, card, 'STRESS', stress, error, range=failure_stress_range); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'HARDENING STRAIN=.. STRESS=.. after PLASTIC TABLE')
    if (allocated(error)) return
    associate (curve => material%hardening)
    n = size(curve%stress)
    if (n == 0 .and. strain /= 0.0_dp) then
      call card_error(error, cards, card, 'the first HARDENING point is the initial yield stress: STRAIN=0, got '// &
                      short_real(strain), field_column(card, 'STRAIN')); return
    end if
    if (n > 0) then
      if (strain <= curve%plastic_strain(n)) then
        call card_error(error, cards, card, 'the HARDENING strains must increase: STRAIN='//short_real(strain)// &
          ' is not above the previous point''s '//short_real(curve%plastic_strain(n)), field_column(card, 'STRAIN'))
        return
      end if
      if (stress < curve%stress(n)) then
        call card_error(error, cards, card, 'softening is not supported: STRESS='//short_real(stress)// &
          ' Pa is below the previous point''s '//short_real(curve%stress(n))//' Pa (the stresses must not '// &
          'decrease along the curve)', field_column(card, 'STRESS')); return
      end if
    end if
    curve%plastic_strain = [curve%plastic_strain, strain]
    curve%stress = [curve%stress, stress]
    end associate
  end subroutine read_hardening

  !> Complete a material once its cards are read: the viscoelastic part
  !> (finish_viscoelastic), then its hardening curve (finish_plastic).
  subroutine finish_material(cards, material, error)
    type(card_deck_t), intent(in) :: cards
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    call finish_viscoelastic(cards, material, error); if (allocated(error)) return
    call finish_foam(cards, material, error); if (allocated(error)) return
    call finish_plastic(cards, material, error)
  end subroutine finish_material

  !> A HYPERFOAM material needs an OGDEN term; its small-strain moduli are
  !> mu0 = sum mu_i and K0 = sum 2 mu_i (1/3 + beta_i), beta_i = nu_i / (1 - 2 nu_i)
  !> (the linear pad it becomes in a small-strain run), both positive.
  subroutine finish_foam(cards, material, error)
    type(card_deck_t), intent(in) :: cards
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    if (material%hyperelastic /= hyperelastic_foam) return
    do k = 1, cards%count
      if (cards%cards(k)%line == material%line) exit
    end do
    if (size(material%foam_mu) == 0) then
      call card_error(error, cards, cards%cards(k), 'material '//material%id//' needs at least one OGDEN MU=.. '// &
                      'ALPHA=.. NU=.. card after it'); return
    end if
    material%shear = sum(material%foam_mu)
    material%bulk = sum(2.0_dp*material%foam_mu*(1.0_dp/3.0_dp + material%foam_nu/(1.0_dp - 2.0_dp*material%foam_nu)))
    if (.not. (material%shear > 0.0_dp .and. material%bulk > 0.0_dp)) then
      call card_error(error, cards, cards%cards(k), 'material '//material%id//': its OGDEN terms give an initial '// &
        'shear modulus sum(mu) = '//short_real(material%shear)//' Pa and bulk modulus '//short_real(material%bulk)// &
        ' Pa; both must be positive'); return
    end if
    call instantaneous_e_nu(material)
    if (.not. conditioned(material)) then
      call card_error(error, cards, cards%cards(k), ratio_message(material)); return
    end if
    material%long_term_shear = material%shear
  end subroutine finish_foam

  !> The hardening curve of a PLASTIC material: a table needs a point; the
  !> bilinear curve needs 0 <= E_t < E (E instantaneous), H = E E_t / (E - E_t).
  subroutine finish_plastic(cards, material, error)
    type(card_deck_t), intent(in) :: cards
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    if (.not. material%plastic) return
    do k = 1, cards%count
      if (cards%cards(k)%line == material%plastic_line) exit
    end do
    if (material%plastic_table) then
      if (size(material%hardening%stress) == 0) call card_error(error, cards, cards%cards(k), 'material '// &
        material%id//': PLASTIC TABLE needs HARDENING cards after it, the first STRAIN=0 STRESS=<initial yield>', &
        material%plastic_column)
      return
    end if
    if (material%plastic_tangent >= material%young) then
      call card_error(error, cards, cards%cards(k), 'TANGENT must be below the Young''s modulus of material '// &
        material%id//', E = '//short_real(material%young)//' Pa (0 <= E_t < E: E_t = E would be no yield at '// &
        'all), got '//short_real(material%plastic_tangent)//' Pa', material%plastic_column); return
    end if
    material%hardening = bilinear_hardening(material%plastic_yield, material%plastic_tangent, material%young)
  end subroutine finish_plastic

  !> Complete a material once its PRONY cards are read: convert a uniaxial
  !> series (eq. [48], exactly), fold beta = 0 terms into G_inf, sort the
  !> memory terms by rate, and set the instantaneous G, E and nu.
  subroutine finish_viscoelastic(cards, material, error)
    type(card_deck_t), intent(in) :: cards
    type(material_t), intent(inout) :: material
    type(error_t), allocatable, intent(inout) :: error
    real(dp), allocatable :: shear(:), rate(:)
    type(error_t), allocatable :: conversion
    integer, allocatable :: order(:)
    if (material%kind == material_kind_elastic) return
    if (material%kind == material_kind_uniaxial) then
      if (size(material%uniaxial_young) == 0) then
        call material_error('material '//material%id//' needs at least one PRONY E=.. ALPHA=.. card'); return
      end if
      call uniaxial_to_shear(material%uniaxial_young, material%uniaxial_rate, material%poisson, &
                             material%bulk, shear, rate, conversion)
      if (allocated(conversion)) then
        call material_error('material '//material%id//': the uniaxial series does not convert to shear: '// &
                            conversion%message); return
      end if
    else
      if (size(material%prony_shear) == 0) then
        call material_error('material '//material%id//' needs at least one PRONY G=.. BETA=.. card'); return
      end if
      shear = material%prony_shear
      rate = material%prony_rate
    end if
    material%long_term_shear = sum(shear, mask=rate == 0.0_dp)
    shear = pack(shear, rate > 0.0_dp)
    rate = pack(rate, rate > 0.0_dp)
    order = sorted_order(rate)                  ! by increasing rate
    material%prony_shear = shear(order)
    material%prony_rate = rate(order)
    material%shear = material%long_term_shear + sum(material%prony_shear)
    call instantaneous_e_nu(material)
    if (.not. conditioned(material)) call material_error(ratio_message(material), material%card_column)
  contains
    subroutine material_error(message, column)
      character(*), intent(in) :: message
      integer, intent(in), optional :: column
      integer :: k
      do k = 1, cards%count
        if (cards%cards(k)%line == material%line) then
          call card_error(error, cards, cards%cards(k), message, column)
          return
        end if
      end do
    end subroutine material_error
  end subroutine finish_viscoelastic

  !> The instantaneous K/G within [1/limit, limit] (nu within about
  !> (-1 + 1e-6, 0.5 - 1e-6)): beyond, the stiffness mixes terms 1e6 times apart
  !> and the shear response drowns in the round-off of the bulk one.
  pure logical function conditioned(material)
    type(material_t), intent(in) :: material
    conditioned = material%bulk <= bulk_shear_ratio_limit*material%shear .and. &
                  material%shear <= bulk_shear_ratio_limit*material%bulk
  end function conditioned

  function ratio_message(material) result(message)
    type(material_t), intent(in) :: material
    character(:), allocatable :: message
    message = 'material '//material%id//': K/G = '//message_real(material%bulk/material%shear)//' (nu = '// &
      short_real(material%poisson)//') is outside ['//compact_real(1.0_dp/bulk_shear_ratio_limit)//', '// &
      compact_real(bulk_shear_ratio_limit)//']: the stiffness would be ill-conditioned '// &
      '(nu closer than 5e-7 to 0.5, or than 1e-6 to -1)'
  end function ratio_message

  !> E and nu of the instantaneous moduli G(0), K.
  pure subroutine instantaneous_e_nu(material)
    type(material_t), intent(inout) :: material
    material%young = 9.0_dp*material%bulk*material%shear/(3.0_dp*material%bulk + material%shear)
    material%poisson = (3.0_dp*material%bulk - 2.0_dp*material%shear)/ &
                       (2.0_dp*(3.0_dp*material%bulk + material%shear))
  end subroutine instantaneous_e_nu
end module visco2d_material_cards
