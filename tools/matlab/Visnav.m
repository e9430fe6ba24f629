% Visnav: the flight navigation pipeline (libvisnav) as an Octave/MATLAB object, for simulation loops.
%
%   nav = Visnav(config, camera, model)     % '' for the built-in defaults / the config's [files]
%   sol = nav.step(image, t_ns)             % image: height x width uint8 (or uint16, bit depth 16)
%   sol = nav.step(image, t_ns, 12)         % uint16 pixels with 12-bit codes
%   sol = nav.step([], t_ns)                % a cycle without a frame (the Kalman filter coasts)
%   ack = nav.command('force_far_range')    % 'reacquire', 'standby', 'resume'
%   nav.startNearRange(position_m, quaternion_wxyz)
%   delete(nav)                             % or let it go out of scope
%
% sol is a struct: mode_name, track_status_name, pose_valid, position_m (t_c_m, 3x1), quaternion (q_c_m,
% w x y z), ypr_rad, covariance (6x6 over omega, dt), quality, fault_bits/fault_names, far_valid,
% far_direction_c, far_distance_m, ... (tools/matlab/README.md lists every field). Frames must come in
% exposure order with increasing t_ns (nanoseconds; int64 keeps them exact beyond 2^53).
classdef Visnav < handle
  properties (SetAccess = private)
    id = 0;  % visnav_mex handle
  end

  methods
    function obj = Visnav(config, camera, model)
      if nargin < 1, config = ''; end
      if nargin < 2, camera = ''; end
      if nargin < 3, model = ''; end
      obj.id = visnav_mex('create', config, camera, model);
    end

    function sol = step(obj, image, t_ns, bit_depth)
      if nargin < 4
        sol = visnav_mex('step', obj.id, image, t_ns);
      else
        sol = visnav_mex('step', obj.id, image, t_ns, bit_depth);
      end
    end

    function ack = command(obj, kind, command_id)
      if nargin < 3, command_id = 0; end
      ack = visnav_mex('command', obj.id, kind, command_id);
    end

    function startNearRange(obj, position_m, quaternion_wxyz)
      visnav_mex('start_near_range', obj.id, double(position_m(:)), double(quaternion_wxyz(:)));
    end

    function timing(obj, on)
      visnav_mex('timing', obj.id, on);
    end

    function delete(obj)
      if obj.id ~= 0
        visnav_mex('destroy', obj.id);
        obj.id = 0;
      end
    end
  end

  methods (Static)
    function v = version()
      v = visnav_mex('version');
    end
  end
end
