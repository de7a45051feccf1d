!> Restart files (&run checkpoint, spallbar DECK --restart FILE, INTERFACE.md).
!>
!> A checkpoint holds everything a run needs to go on as if it had never stopped: every
!> component of state_t (float64 written and read back bit for bit), the summary the run
!> carries from step to step (the energy guard's reference and scale among it) and the
!> marks of its outputs (bytes of each text file, rows of each PREFIX.h5 table). With it,
!> what identifies the run, checked on restart: the program version, the deck (every echoed
!> value except title, t_end, checkpoint, checkpoint_every and profile times after the
!> checkpoint), the mesh's dt and cells, a load table's values. Layout in doc/outputs.md.
!> The file is written as FILE.part and renamed: a run killed while writing it keeps the
!> previous checkpoint.
module spb_checkpoint
   use, intrinsic :: iso_fortran_env, only: int64
   use spb_kinds, only: wp, version
   use spb_error, only: spb_error_t, make_error, exit_input, exit_runtime
   use spb_strings, only: itoa, rtoa
   use spb_deck, only: deck_t, deck_items, echo_item_t
   use spb_mesh, only: mesh_t
   use spb_load, only: load_t, load_table
   use spb_state, only: state_t
   use spb_diag, only: run_summary_t
   use spb_output, only: output_marks_t, h5_deck_header, text_extensions, tail_len
   use spb_hdf5, only: h5file_t, h5_create, h5_open_read, h5_close, h5_group, h5_attr, &
      h5_write, h5_get, h5_get_attr
   use spb_sys, only: sys_rename
   implicit none
   private
   public :: checkpoint_t, write_checkpoint, read_checkpoint, check_checkpoint_path

   character(len=*), parameter :: format_name = 'spallbar checkpoint 1'
   character(len=1), parameter :: nl = achar(10)

   !> What a restart continues from.
   type :: checkpoint_t
      type(state_t) :: st
      type(run_summary_t) :: summary
      type(output_marks_t) :: marks
   end type checkpoint_t

contains

   !> Refuse (exit 2) a checkpoint path that cannot be written, before the run starts.
   subroutine check_checkpoint_path(path, err)
      character(len=*), intent(in) :: path
      type(spb_error_t), allocatable, intent(out) :: err
      integer :: u, ios
      character(len=256) :: msg
      open(newunit=u, file=path // '.part', status='replace', action='write', iostat=ios, &
           iomsg=msg)
      if (ios /= 0) then
         call make_error(err, '&run: checkpoint = ''' // path // ''': cannot write ''' // &
                         path // '.part'': ' // trim(msg))
         return
      end if
      close(u, status='delete')
   end subroutine check_checkpoint_path

   !> Write the checkpoint of a run at its state's step.
   subroutine write_checkpoint(path, deck, mesh, load, st, summary, marks, err)
      character(len=*), intent(in) :: path
      type(deck_t), intent(in) :: deck
      type(mesh_t), intent(in) :: mesh
      type(load_t), intent(in) :: load
      type(state_t), intent(in) :: st
      type(run_summary_t), intent(in) :: summary
      type(output_marks_t), intent(in) :: marks
      type(spb_error_t), allocatable, intent(out) :: err
      type(h5file_t) :: h5
      logical :: ok
      integer :: k
      call h5_create(h5, path // '.part')
      call h5_deck_header(h5, deck)
      call h5_attr(h5, '/', 'format', format_name)
      call h5_attr(h5, '/', 'step', st%n)
      call h5_attr(h5, '/', 't', real(st%n, wp) * mesh%dt)
      ! what identifies the run
      call h5_group(h5, '/identity')
      call h5_attr(h5, '/identity', 'program', 'spallbar ' // version)
      call h5_attr(h5, '/identity', 'deck', deck_identity(deck))
      call h5_attr(h5, '/identity', 'dt', mesh%dt)
      call h5_attr(h5, '/identity', 'cells', mesh%n)
      call h5_attr(h5, '/identity', 'n_profiles', deck%run%n_profiles)
      if (deck%run%n_profiles > 0) call h5_write(h5, '/identity/profile_times', &
         deck%run%profile_times(1:deck%run%n_profiles), 's')
      if (load%kind == load_table) then
         call h5_write(h5, '/identity/load_t', load%t, 's')
         call h5_write(h5, '/identity/load_p', load%p, 'Pa')
      end if
      call write_state(h5, st)
      ! the run's summary
      call h5_group(h5, '/run')
      call h5_attr(h5, '/run', 'steps', summary%steps)
      call h5_attr(h5, '/run', 'events', summary%events)
      do k = 1, size(summary%n_kind)
         call h5_attr(h5, '/run', 'n_kind_' // itoa(k), summary%n_kind(k))
      end do
      call h5_attr(h5, '/run', 'checkpoints', summary%checkpoints)
      call h5_attr(h5, '/run', 'ledger0', summary%ledger0)
      call h5_attr(h5, '/run', 'ledger_drift', summary%ledger_drift)
      call h5_attr(h5, '/run', 'energy_scale', summary%energy_scale)
      call h5_attr(h5, '/run', 'max_excess', summary%max_excess)
      call h5_attr(h5, '/run', 'first_fracture_t', summary%first_fracture_t)
      call h5_attr(h5, '/run', 'max_reaction_bottom', summary%max_reaction_bottom)
      call h5_attr(h5, '/run', 'e_kin_end', summary%e_kin_end)
      call h5_attr(h5, '/run', 'w_ext_end', summary%w_ext_end)
      call h5_attr(h5, '/run', 'e_mech0', summary%e_mech0)
      call h5_attr(h5, '/run', 'guard_scale', summary%guard_scale)
      call h5_attr(h5, '/run', 'ledger_w0', summary%ledger_w0)
      call h5_attr(h5, '/run', 'wave_drift', summary%wave_drift)
      call h5_attr(h5, '/run', 'max_jordan', summary%max_jordan)
      call h5_attr(h5, '/run', 'jordan_scale', summary%jordan_scale)
      call h5_attr(h5, '/run', 'fracture_stress_sum', summary%fracture_stress_sum)
      ! how far the outputs reach (byte counts as float64: exact below 2^53)
      call h5_group(h5, '/outputs')
      do k = 1, 4
         call h5_attr(h5, '/outputs', 'body' // text_extensions(k), real(marks%body(k), wp))
         call h5_attr(h5, '/outputs', 'tail_bytes' // text_extensions(k), marks%tail_n(k))
         call h5_attr(h5, '/outputs', 'tail' // text_extensions(k), &
                      marks%tail(k)(1:max(0, marks%tail_n(k))))
      end do
      call h5_attr(h5, '/outputs', 'rows_history', marks%rows_his)
      call h5_attr(h5, '/outputs', 'rows_events', marks%rows_evt)
      call h5_attr(h5, '/outputs', 'rows_xt', marks%rows_xt)
      call h5_attr(h5, '/outputs', 'profiles', marks%n_prof)
      call h5_attr(h5, '/outputs', 'fragment_blocks', marks%n_frg)
      call h5_close(h5)
      if (allocated(h5%error)) then
         call make_error(err, '&run: checkpoint: ' // h5%error, code=exit_runtime)
         return
      end if
      call sys_rename(path // '.part', path, ok)
      if (.not. ok) call make_error(err, '&run: checkpoint: cannot rename ''' // path // &
                                    '.part'' to ''' // path // '''', code=exit_runtime)
   end subroutine write_checkpoint

   !> Every component of state_t: arrays as datasets under /state with their lower bound
   !> and size as attributes of /state, scalars as attributes, logicals as 0/1.
   subroutine write_state(h5, st)
      type(h5file_t), intent(inout) :: h5
      type(state_t), intent(in) :: st
      call h5_group(h5, '/state')
      call put_int('n', st%n)
      call put_int('n_breakable', st%n_breakable)
      call put_int('n_split', st%n_split)
      call put_int('n_frag_ids', st%n_frag_ids)
      call put_int('n_cut', st%n_cut)
      call put_int('n_skip', st%n_skip)
      call put_real('s_scale', st%s_scale)
      call put_real('strain_cut', st%strain_cut)
      call put_real('e_contact', st%e_contact)
      call put_real('s_static_top', st%s_static_top)
      call put_real('s_static_bot', st%s_static_bot)
      call put_real('v_far_top', st%v_far_top)
      call put_real('v_far_bot', st%v_far_bot)
      call put_real('w_in_top', st%w_in_top)
      call put_real('w_in_bot', st%w_in_bot)
      call put_real('w_load', st%w_load)
      call put_real('w_transmit', st%w_transmit)
      call put_real('e_fracture', st%e_fracture)
      call put_real('e_join', st%e_join)
      call put_real('e_shift', st%e_shift)
      call put_real('p_shift', st%p_shift)
      call put_real('w_wave', st%w_wave)
      call put_real('e_lost_wave', st%e_lost_wave)
      call put_real('i_ends', st%i_ends)
      call put_real('i_support', st%i_support)
      call put_real('u_base', st%u_base)
      call put_real('v_land_top', st%v_land_top)
      call put_real('v_land_bot', st%v_land_bot)
      call put_int('base_contact', merge(1, 0, st%base_contact))
      call put_int('landing_top', merge(1, 0, st%landing_top))
      call put_int('landing_bot', merge(1, 0, st%landing_bot))
      call put_reals('ua', st%ua)
      call put_reals('ub', st%ub)
      call put_reals('dua', st%dua)
      call put_reals('dub', st%dub)
      call put_reals('s', st%s)
      call put_reals('s_old', st%s_old)
      call put_reals('sec', st%sec)
      call put_reals('strength', st%strength)
      call put_reals('cell_strength', st%cell_strength)
      call put_ints('split', st%split)
      call put_ints('frag_id', st%frag_id)
      call put_ints('frag_parent', st%frag_parent)
      call put_ints('frag_birth', st%frag_birth)
      call put_ints('cut', st%cut)
      call put_ints('skip_test', st%skip_test)
      call put_logicals('joined', st%joined)
      call put_logicals('is_cut', st%is_cut)
      call put_logicals('cracked', st%cracked)
   contains
      subroutine put_int(name, v)
         character(len=*), intent(in) :: name
         integer, intent(in) :: v
         call h5_attr(h5, '/state', name, v)
      end subroutine put_int
      subroutine put_real(name, v)
         character(len=*), intent(in) :: name
         real(wp), intent(in) :: v
         call h5_attr(h5, '/state', name, v)
      end subroutine put_real
      subroutine bounds(name, lb, n)
         character(len=*), intent(in) :: name
         integer, intent(in) :: lb, n
         call h5_attr(h5, '/state', name // ':lbound', lb)
         call h5_attr(h5, '/state', name // ':size', n)
      end subroutine bounds
      subroutine put_reals(name, a)
         character(len=*), intent(in) :: name
         real(wp), allocatable, intent(in) :: a(:)
         if (.not. allocated(a)) return
         call bounds(name, lbound(a, 1), size(a))
         if (size(a) > 0) call h5_write(h5, '/state/' // name, a, '-')
      end subroutine put_reals
      subroutine put_ints(name, a)
         character(len=*), intent(in) :: name
         integer, allocatable, intent(in) :: a(:)
         if (.not. allocated(a)) return
         call bounds(name, lbound(a, 1), size(a))
         if (size(a) > 0) call h5_write(h5, '/state/' // name, a, '-')
      end subroutine put_ints
      subroutine put_logicals(name, a)
         character(len=*), intent(in) :: name
         logical, allocatable, intent(in) :: a(:)
         integer, allocatable :: v(:)
         if (.not. allocated(a)) return
         allocate(v(lbound(a, 1):ubound(a, 1)), source=merge(1, 0, a))
         call put_ints(name, v)
      end subroutine put_logicals
   end subroutine write_state

   !> Read a checkpoint for the run set up from deck (mesh, load) and check that the
   !> restart can be identical to an uninterrupted run; every refusal is exit status 2.
   subroutine read_checkpoint(path, deck, mesh, load, ck, err)
      character(len=*), intent(in) :: path
      type(deck_t), intent(in) :: deck
      type(mesh_t), intent(in) :: mesh
      type(load_t), intent(in) :: load
      type(checkpoint_t), intent(out) :: ck
      type(spb_error_t), allocatable, intent(out) :: err
      type(h5file_t) :: h5
      character(len=:), allocatable :: text, here
      real(wp) :: x
      real(wp), allocatable :: times(:), tab(:)
      integer :: k, i
      logical :: exists
      inquire(file=path, exist=exists)
      if (.not. exists) then
         call make_error(err, '--restart: ''' // path // ''' does not exist')
         return
      end if
      call h5_open_read(h5, path)
      if (allocated(h5%error)) then
         call make_error(err, '--restart: ''' // path // ''' is not an HDF5 file (' // &
                         h5%error // ')')
         return
      end if
      call h5_get_attr(h5, '/', 'format', text)
      if (text /= format_name .or. allocated(h5%error)) then
         call refuse('is not a spallbar checkpoint (no root attribute format = ''' // &
                     format_name // ''')')
         return
      end if
      call h5_get_attr(h5, '/identity', 'program', text)
      if (text /= 'spallbar ' // version) then
         call refuse('was written by ' // text // ', this is spallbar ' // version // &
                     ' (a restart is bit-identical only with the program that wrote it)')
         return
      end if
      ! the deck
      call h5_get_attr(h5, '/identity', 'deck', text)
      here = deck_identity(deck)
      if (text /= here) then
         call refuse('was written for another deck: ' // first_difference(text, here) // &
                     ' (only title, t_end, checkpoint, checkpoint_every and later ' // &
                     'profile_times may change)')
         return
      end if
      call h5_get_attr(h5, '/identity', 'dt', x)
      call h5_get_attr(h5, '/identity', 'cells', i)
      if (.not. same([x], [mesh%dt]) .or. i /= mesh%n) then
         call refuse('has dt = ' // rtoa(x) // ' s and ' // itoa(i) // ' cells, this ' // &
                     'deck''s mesh dt = ' // rtoa(mesh%dt) // ' s and ' // itoa(mesh%n) // ' cells')
         return
      end if
      if (load%kind == load_table) then
         call h5_get(h5, '/identity/load_t', tab)
         if (.not. allocated(tab)) allocate(tab(0))
         if (.not. same(tab, load%t)) then
            call refuse('was written with another &load table (its times differ from ''' // &
                        trim(deck%load%table) // ''')')
            return
         end if
         call h5_get(h5, '/identity/load_p', tab)
         if (.not. allocated(tab)) allocate(tab(0))
         if (.not. same(tab, load%p)) then
            call refuse('was written with another &load table (its pressures differ from ''' &
                        // trim(deck%load%table) // ''')')
            return
         end if
      end if
      call read_state(h5, ck%st)
      if (allocated(h5%error)) then
         call refuse('cannot be read: ' // h5%error)
         return
      end if
      if (.not. allocated(ck%st%ua)) then
         call refuse('has no state')
         return
      end if
      if (lbound(ck%st%ua, 1) /= 0 .or. ubound(ck%st%ua, 1) /= mesh%n) then
         call refuse('holds a state of ' // itoa(size(ck%st%ua) - 1) // ' cells, the mesh ' // &
                     'has ' // itoa(mesh%n))
         return
      end if
      if (ck%st%n > mesh%nsteps) then
         call refuse('is at step ' // itoa(ck%st%n) // ' (t = ' // &
                     rtoa(real(ck%st%n, wp) * mesh%dt) // ' s), after this deck''s t_end = ' // &
                     rtoa(deck%run%t_end) // ' s (' // itoa(mesh%nsteps) // ' steps)')
         return
      end if
      ! profile times up to the checkpoint are in the outputs already: they must not change
      call h5_get_attr(h5, '/identity', 'n_profiles', i)
      if (i > 0) then
         call h5_get(h5, '/identity/profile_times', times)
      end if
      if (.not. allocated(times)) then
         allocate(times(0))
      end if
      if (.not. same(pack(times, nint(times / mesh%dt) <= ck%st%n), &
                     pack(deck%run%profile_times(1:deck%run%n_profiles), &
                          nint(deck%run%profile_times(1:deck%run%n_profiles) / mesh%dt) <= &
                          ck%st%n))) then
         call refuse('has other profile_times up to its t = ' // &
                     rtoa(real(ck%st%n, wp) * mesh%dt) // ' s than &run profile_times here')
         return
      end if
      ! the run's summary
      call h5_get_attr(h5, '/run', 'steps', ck%summary%steps)
      call h5_get_attr(h5, '/run', 'events', ck%summary%events)
      do k = 1, size(ck%summary%n_kind)
         call h5_get_attr(h5, '/run', 'n_kind_' // itoa(k), ck%summary%n_kind(k))
      end do
      call h5_get_attr(h5, '/run', 'checkpoints', ck%summary%checkpoints)
      call h5_get_attr(h5, '/run', 'ledger0', ck%summary%ledger0)
      call h5_get_attr(h5, '/run', 'ledger_drift', ck%summary%ledger_drift)
      call h5_get_attr(h5, '/run', 'energy_scale', ck%summary%energy_scale)
      call h5_get_attr(h5, '/run', 'max_excess', ck%summary%max_excess)
      call h5_get_attr(h5, '/run', 'first_fracture_t', ck%summary%first_fracture_t)
      call h5_get_attr(h5, '/run', 'max_reaction_bottom', ck%summary%max_reaction_bottom)
      call h5_get_attr(h5, '/run', 'e_kin_end', ck%summary%e_kin_end)
      call h5_get_attr(h5, '/run', 'w_ext_end', ck%summary%w_ext_end)
      call h5_get_attr(h5, '/run', 'e_mech0', ck%summary%e_mech0)
      call h5_get_attr(h5, '/run', 'guard_scale', ck%summary%guard_scale)
      call h5_get_attr(h5, '/run', 'ledger_w0', ck%summary%ledger_w0)
      call h5_get_attr(h5, '/run', 'wave_drift', ck%summary%wave_drift)
      call h5_get_attr(h5, '/run', 'max_jordan', ck%summary%max_jordan)
      call h5_get_attr(h5, '/run', 'jordan_scale', ck%summary%jordan_scale)
      call h5_get_attr(h5, '/run', 'fracture_stress_sum', ck%summary%fracture_stress_sum)
      do k = 1, 4
         call h5_get_attr(h5, '/outputs', 'body' // text_extensions(k), x)
         ck%marks%body(k) = int(x, kind(ck%marks%body))
         call h5_get_attr(h5, '/outputs', 'tail_bytes' // text_extensions(k), ck%marks%tail_n(k))
         call h5_get_attr(h5, '/outputs', 'tail' // text_extensions(k), text)
         ! a string attribute comes back without trailing blanks: pad to its length
         ck%marks%tail(k) = text
         if (ck%marks%tail_n(k) > tail_len) then
            call refuse('holds a tail of ' // itoa(ck%marks%tail_n(k)) // ' bytes for ' // &
                        text_extensions(k) // ' (at most ' // itoa(tail_len) // ')')
            return
         end if
      end do
      call h5_get_attr(h5, '/outputs', 'rows_history', ck%marks%rows_his)
      call h5_get_attr(h5, '/outputs', 'rows_events', ck%marks%rows_evt)
      call h5_get_attr(h5, '/outputs', 'rows_xt', ck%marks%rows_xt)
      call h5_get_attr(h5, '/outputs', 'profiles', ck%marks%n_prof)
      call h5_get_attr(h5, '/outputs', 'fragment_blocks', ck%marks%n_frg)
      if (allocated(h5%error)) then
         call refuse('cannot be read: ' // h5%error)
         return
      end if
      call h5_close(h5)
   contains
      subroutine refuse(why)
         character(len=*), intent(in) :: why
         call make_error(err, '--restart: ''' // path // ''' ' // why, code=exit_input)
         call h5_close(h5)
      end subroutine refuse
   end subroutine read_checkpoint

   !> Inverse of write_state.
   subroutine read_state(h5, st)
      type(h5file_t), intent(inout) :: h5
      type(state_t), intent(out) :: st
      integer :: flag
      call h5_get_attr(h5, '/state', 'n', st%n)
      call h5_get_attr(h5, '/state', 'n_breakable', st%n_breakable)
      call h5_get_attr(h5, '/state', 'n_split', st%n_split)
      call h5_get_attr(h5, '/state', 'n_frag_ids', st%n_frag_ids)
      call h5_get_attr(h5, '/state', 'n_cut', st%n_cut)
      call h5_get_attr(h5, '/state', 'n_skip', st%n_skip)
      call h5_get_attr(h5, '/state', 's_scale', st%s_scale)
      call h5_get_attr(h5, '/state', 'strain_cut', st%strain_cut)
      call h5_get_attr(h5, '/state', 'e_contact', st%e_contact)
      call h5_get_attr(h5, '/state', 's_static_top', st%s_static_top)
      call h5_get_attr(h5, '/state', 's_static_bot', st%s_static_bot)
      call h5_get_attr(h5, '/state', 'v_far_top', st%v_far_top)
      call h5_get_attr(h5, '/state', 'v_far_bot', st%v_far_bot)
      call h5_get_attr(h5, '/state', 'w_in_top', st%w_in_top)
      call h5_get_attr(h5, '/state', 'w_in_bot', st%w_in_bot)
      call h5_get_attr(h5, '/state', 'w_load', st%w_load)
      call h5_get_attr(h5, '/state', 'w_transmit', st%w_transmit)
      call h5_get_attr(h5, '/state', 'e_fracture', st%e_fracture)
      call h5_get_attr(h5, '/state', 'e_join', st%e_join)
      call h5_get_attr(h5, '/state', 'e_shift', st%e_shift)
      call h5_get_attr(h5, '/state', 'p_shift', st%p_shift)
      call h5_get_attr(h5, '/state', 'w_wave', st%w_wave)
      call h5_get_attr(h5, '/state', 'e_lost_wave', st%e_lost_wave)
      call h5_get_attr(h5, '/state', 'i_ends', st%i_ends)
      call h5_get_attr(h5, '/state', 'i_support', st%i_support)
      call h5_get_attr(h5, '/state', 'u_base', st%u_base)
      call h5_get_attr(h5, '/state', 'v_land_top', st%v_land_top)
      call h5_get_attr(h5, '/state', 'v_land_bot', st%v_land_bot)
      call h5_get_attr(h5, '/state', 'base_contact', flag)
      st%base_contact = flag /= 0
      call h5_get_attr(h5, '/state', 'landing_top', flag)
      st%landing_top = flag /= 0
      call h5_get_attr(h5, '/state', 'landing_bot', flag)
      st%landing_bot = flag /= 0
      call get_reals('ua', st%ua)
      call get_reals('ub', st%ub)
      call get_reals('dua', st%dua)
      call get_reals('dub', st%dub)
      call get_reals('s', st%s)
      call get_reals('s_old', st%s_old)
      call get_reals('sec', st%sec)
      call get_reals('strength', st%strength)
      call get_reals('cell_strength', st%cell_strength)
      call get_ints('split', st%split)
      call get_ints('frag_id', st%frag_id)
      call get_ints('frag_parent', st%frag_parent)
      call get_ints('frag_birth', st%frag_birth)
      call get_ints('cut', st%cut)
      call get_ints('skip_test', st%skip_test)
      call get_logicals('joined', st%joined)
      call get_logicals('is_cut', st%is_cut)
      call get_logicals('cracked', st%cracked)
   contains
      !> Lower bound and size of an array (a missing one is an error in h5%error).
      subroutine bounds(name, lb, n)
         character(len=*), intent(in) :: name
         integer, intent(out) :: lb, n
         n = -1
         call h5_get_attr(h5, '/state', name // ':lbound', lb)
         call h5_get_attr(h5, '/state', name // ':size', n)
         if (allocated(h5%error)) n = -1
      end subroutine bounds
      subroutine get_reals(name, a)
         character(len=*), intent(in) :: name
         real(wp), allocatable, intent(out) :: a(:)
         real(wp), allocatable :: v(:)
         integer :: lb, n
         call bounds(name, lb, n)
         if (n < 0) return
         if (n > 0) call h5_get(h5, '/state/' // name, v)
         if (.not. allocated(v)) allocate(v(0))
         if (have(name, size(v), n)) allocate(a(lb:lb + n - 1), source=v)
      end subroutine get_reals
      !> Integers come back through float64 (HDF5 converts; exact below 2^53).
      subroutine get_ints(name, a)
         character(len=*), intent(in) :: name
         integer, allocatable, intent(out) :: a(:)
         real(wp), allocatable :: v(:)
         call get_reals(name, v)
         if (allocated(v)) allocate(a(lbound(v, 1):ubound(v, 1)), source=nint(v))
      end subroutine get_ints
      subroutine get_logicals(name, a)
         character(len=*), intent(in) :: name
         logical, allocatable, intent(out) :: a(:)
         integer, allocatable :: v(:)
         call get_ints(name, v)
         if (allocated(v)) allocate(a(lbound(v, 1):ubound(v, 1)), source=v /= 0)
      end subroutine get_logicals
      !> The dataset holds the size its attribute states (else an error in h5%error).
      logical function have(name, got, n)
         character(len=*), intent(in) :: name
         integer, intent(in) :: got, n
         have = got == n
         if (.not. have .and. .not. allocated(h5%error)) h5%error = '/state/' // name // &
            ' holds ' // itoa(got) // ' values, its :size attribute says ' // itoa(n)
      end function have
   end subroutine read_state

   !> The deck values a restart must not change: 'group name = value' lines of the echo,
   !> without title, t_end, checkpoint, checkpoint_every and profile_times (checked apart).
   function deck_identity(deck) result(text)
      type(deck_t), intent(in) :: deck
      character(len=:), allocatable :: text
      type(echo_item_t), allocatable :: items(:)
      integer :: k
      call deck_items(deck, items)
      text = ''
      do k = 1, size(items)
         if (items(k)%group == 'run') then
            select case (items(k)%name)
            case ('title', 't_end', 'checkpoint', 'checkpoint_every', 'profile_times')
               cycle
            end select
         end if
         text = text // '&' // items(k)%group // ' ' // items(k)%name // ' = ' // &
                items(k)%value // nl
      end do
   end function deck_identity

   !> The first line of a that differs from b, for a message.
   function first_difference(a, b) result(msg)
      character(len=*), intent(in) :: a, b
      character(len=:), allocatable :: msg
      integer :: i, ia, ib
      i = 1
      do while (i <= min(len(a), len(b)))
         if (a(i:i) /= b(i:i)) exit
         i = i + 1
      end do
      ia = index(a(:i - 1), nl, back=.true.) + 1
      ib = index(a(i:), nl)
      if (ib == 0) then
         msg = a(ia:)
      else
         msg = a(ia:i + ib - 2)
      end if
      ib = index(b(i:), nl)
      if (ib == 0) then
         msg = 'there ' // msg // ', here ' // b(ia:)
      else
         msg = 'there ' // msg // ', here ' // b(ia:i + ib - 2)
      end if
   end function first_difference

   !> Two arrays equal bit for bit (and in size).
   pure logical function same(a, b)
      real(wp), intent(in) :: a(:), b(:)
      same = size(a) == size(b)
      if (same) same = all(transfer(a, 0_int64, size(a)) == transfer(b, 0_int64, size(b)))
   end function same
end module spb_checkpoint
