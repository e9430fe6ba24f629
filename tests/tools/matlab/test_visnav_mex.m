% The Octave test of tools/matlab (ctest mex_replay_identity): runs a sequence directory frame by frame
% through the MEX (Visnav.m) and writes visnav-replay's CSV (tools/replay/README.md, same columns and printf
% formats, timing zero like --no-timing), which the ctest script compares byte for byte with visnav-replay's.
% Even frames go in as height x width matrices (copied into the row-major buffer), odd ones transposed
% (used in place): both paths must give the same numbers. Also checks the error paths. Exit status 1 on any
% failure.
function test_visnav_mex(sequence_dir, config, out_csv)
  v = Visnav.version();
  assert(v.abi == v.header_abi, 'ABI mismatch');
  printf('libvisnav %s (ABI %d)\n', v.version, v.abi);

  % Errors are Octave errors with the library's text, never a crash.
  try
    Visnav(config, '/nonexistent/camera.toml', [sequence_dir '/model.toml']);
    error('test:fail', 'a missing camera file was accepted');
  catch e
    assert(strcmp(e.identifier, 'visnav:create'), e.message);
    assert(!isempty(strfind(e.message, '/nonexistent/camera.toml')), e.message);
  end
  try
    visnav_mex('step', 12345, uint8(zeros(2)), 0);
    error('test:fail', 'a made-up handle was accepted');
  catch e
    assert(strcmp(e.identifier, 'visnav:handle'), e.message);
  end

  nav = Visnav(config, [sequence_dir '/camera.toml'], [sequence_dir '/model.toml']);
  fid = fopen([sequence_dir '/frames.csv'], 'r');
  header = fgetl(fid);
  assert(strcmp(header, 'frame,timestamp_ns,file'), header);
  list = textscan(fid, '%d64 %d64 %s', 'Delimiter', ',');
  fclose(fid);
  frames = list{1};
  stamps = list{2};
  files = list{3};

  out = fopen(out_csv, 'w');
  fputs(out, 'frame,timestamp_ns,status,flags,mode,quality,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg');
  for i = 0:5
    for j = 0:5
      fprintf(out, ',cov_%d_%d', i, j);
    end
  end
  fputs(out, [',tracked_surfaces,surface_mask,lines_total,lines_used,edge_points,inlier_points,texture_points,' ...
              'vertices,rms_px,lm_iterations,t_project_us,t_scan_us,t_ransac_us,t_pose_us,t_total_us,' ...
              'fault_bits,far_valid,far_azimuth_deg,far_elevation_deg,far_distance_m,far_cluster_px,far_circularity,' ...
              'far_clusters,nis,symmetric_twins,twin_by_continuity' "\n"]);
  deg = 180 / pi;
  modes = zeros(1, 4);
  for k = 1:numel(frames)
    [image, maxval] = read_pgm([sequence_dir '/' files{k}]);
    if mod(k - 1, 2) == 0
      input = image;      % height x width: the MEX copies it into row-major order
    else
      input = image.';    % width x height: already row-major in memory, used in place
    end
    if maxval > 255
      sol = nav.step(input, stamps(k), round(log2(double(maxval) + 1)));
    else
      sol = nav.step(input, stamps(k));
    end
    assert(sol.frame_number == uint64(k - 1));
    modes(sol.mode + 1) += 1;
    fprintf(out, '%d,%d,%s,%d,%s,%.6f', double(frames(k)), double(stamps(k)), sol.track_status_name, ...
            sol.track_flags, sol.mode_name, sol.quality);
    if sol.pose_valid
      fprintf(out, ',%.12g', [sol.position_m; sol.quaternion; sol.ypr_rad * deg]);
      fprintf(out, ',%.6g', sol.covariance.');  % row by row
    else
      fputs(out, repmat(',', 1, 46));
    end
    fprintf(out, ',%d,%d,%d,%d,%d,%d,%d,%d,%.6f,%d,%.2f,%.2f,%.2f,%.2f,%.2f', sol.tracked_surfaces, ...
            double(sol.tracked_surface_mask), sol.lines_total, sol.lines_used, sol.edge_points, ...
            sol.inlier_points, sol.texture_points, sol.vertices, sol.rms_px, sol.lm_iterations, ...
            sol.t_project_us, sol.t_scan_us, sol.t_ransac_us, sol.t_pose_us, sol.t_process_us);
    fprintf(out, ',%d,%d,%.9g,%.9g,%.9g,%d,%.6f,%d,', sol.fault_bits, sol.far_valid, ...
            sol.far_azimuth_rad * deg, sol.far_elevation_rad * deg, sol.far_distance_m, ...
            sol.far_cluster_pixels, sol.far_circularity, sol.far_cluster_count);
    if sol.nis_valid
      fprintf(out, '%.6g', sol.nis);
    end
    fprintf(out, ',%d,%d\n', sol.symmetric_twins, sol.twin_by_continuity);
  end
  fclose(out);

  % A cycle without a frame and the commands, after the sequence.
  sol = nav.step([], stamps(end) + int64(200000000));
  assert(sol.frame_received == 0 && !isempty(strfind(sol.fault_names, 'no_frame')), sol.fault_names);
  ack = nav.command('resume', 5);
  assert(ack.accepted == 0 && strcmp(ack.reason, 'not in standby'), ack.reason);
  ack = nav.command('force_far_range', 6);
  assert(ack.accepted == 1 && ack.command_id == 6, ack.reason);
  delete(nav);
  printf('mex: %d frames: standby %d, far range %d, acquisition %d, near range %d -> %s\n', numel(frames), ...
         modes(1), modes(2), modes(3), modes(4), out_csv);
end

function [image, maxval] = read_pgm(path)
  fid = fopen(path, 'r');
  assert(fid >= 0, ['cannot open ' path]);
  bytes = fread(fid, Inf, 'uint8=>uint8');
  fclose(fid);
  % Header: P5 width height maxval (whitespace, # comments), one whitespace byte, the raster.
  tokens = {};
  pos = 1;
  while numel(tokens) < 4
    c = bytes(pos);
    if c == '#'
      while bytes(pos) != 10, pos += 1; end
    elseif any(c == [9 10 13 32])
      pos += 1;
    else
      start = pos;
      while !any(bytes(pos) == [9 10 13 32]), pos += 1; end
      tokens{end + 1} = char(bytes(start:pos - 1).');
    end
  end
  assert(strcmp(tokens{1}, 'P5'), [path ': not a binary PGM']);
  width = str2double(tokens{2});
  height = str2double(tokens{3});
  maxval = str2double(tokens{4});
  raster = bytes(pos + 1:end);
  if maxval > 255  % big-endian 16-bit samples
    raster = uint16(raster(1:2:end)) * 256 + uint16(raster(2:2:end));
  end
  assert(numel(raster) == width * height, [path ': raster size']);
  image = reshape(raster, width, height).';  % rows of the file -> rows of the matrix
end
